"""A real rospy node driven over stdin/stdout with JSON lines (run by /usr/bin/python3).

Message classes come from the morai_msgs contract's definitions through genpy's
dynamic generation, exactly as a client compiled against morai_msgs would have them.

argv: CONTRACT_JSON STANDARD_TYPES_JSON NODE_NAME
Each request line is {"op": ..., ...}; each reply line is {"ok": true, "result": ...}
or {"ok": false, "error": "..."}.
"""

import json
import sys
import threading
import time
import traceback

import genpy
import genpy.dynamic
import rospy

with open(sys.argv[1]) as file:
    contract = json.load(file)
with open(sys.argv[2]) as file:
    standard = json.load(file)["types"]
classes = {}


def definition_of(type_name):
    if type_name in contract["messages"]:
        return contract["messages"][type_name]["definition"]
    return standard[type_name]["definition"]


def remember(generated):
    for name, cls in generated.items():
        classes.setdefault(name, cls)


def message_class(type_name):
    if type_name not in classes:
        remember(genpy.dynamic.generate_dynamic(type_name, definition_of(type_name)))
    return classes[type_name]


def service_class(type_name):
    if type_name not in classes:
        spec = contract["services"][type_name]
        remember(genpy.dynamic.generate_dynamic(spec["request"], spec["request_definition"]))
        remember(genpy.dynamic.generate_dynamic(spec["response"], spec["response_definition"]))
        classes[type_name] = type(
            type_name.split("/")[1],
            (),
            {
                "_type": type_name,
                "_md5sum": spec["md5sum"],
                "_request_class": classes[spec["request"]],
                "_response_class": classes[spec["response"]],
            },
        )
    return classes[type_name]


def slot_class(message, name):
    """The generated class of a message-typed slot (of its elements, for arrays)."""
    slot_type = message._slot_types[message.__slots__.index(name)]
    return classes[slot_type.split("[")[0]]


def fill(message, values):
    for name, value in values.items():
        current = getattr(message, name)
        if isinstance(current, (genpy.Time, genpy.Duration)):
            setattr(message, name, type(current)(value["secs"], value["nsecs"]))
        elif isinstance(value, dict):
            fill(current, value)
        elif isinstance(value, list) and value and isinstance(value[0], dict):
            item_class = slot_class(message, name)
            setattr(message, name, [fill(item_class(), item) for item in value])
        else:
            setattr(message, name, value)
    return message


def to_plain(value):
    if isinstance(value, (genpy.Time, genpy.Duration)):
        return value.to_sec()
    if isinstance(value, genpy.Message):
        return {name: to_plain(getattr(value, name)) for name in value.__slots__}
    if isinstance(value, (list, tuple)):
        return [to_plain(item) for item in value]
    if isinstance(value, bytes):
        return {"bytes": len(value)}
    return value


def to_hex(message):
    """A rospy.AnyMsg's serialized bytes, as they came off the wire."""
    return {"hex": message._buff.hex()}


class Inbox:
    def __init__(self, convert=to_plain):
        self.messages = []
        self.condition = threading.Condition()
        self.convert = convert

    def __call__(self, message):
        plain = self.convert(message)
        plain["_received"] = time.time()
        with self.condition:
            self.messages.append(plain)
            self.condition.notify_all()


subscriptions = {}
subscribers = {}
publishers = {}
streams = {}


def op_subscribe(request):
    """Subscribe to topic; with "raw", keep each message's serialized bytes (hex)."""
    topic = request["topic"]
    if topic not in subscriptions:
        raw = request.get("raw", False)
        inbox = Inbox(to_hex if raw else to_plain)
        message_type = rospy.AnyMsg if raw else message_class(request["type"])
        subscribers[topic] = rospy.Subscriber(topic, message_type, inbox, queue_size=1000)
        subscriptions[topic] = inbox
    return True


def op_wait_connected(request):
    """Wait until the subscription to topic has `count` publishers connected."""
    subscriber = subscribers[request["topic"]]
    deadline = time.time() + request.get("timeout", 20.0)
    while subscriber.get_num_connections() < request.get("count", 1):
        if time.time() > deadline:
            raise RuntimeError("no publisher connected to " + request["topic"])
        time.sleep(0.02)
    return True


def op_now(request):
    """The node's ROS time (simulation time when /use_sim_time is set), s."""
    return rospy.get_time()


def op_messages(request):
    inbox = subscriptions[request["topic"]]
    since, count = request.get("since", 0), request.get("count", 1)
    deadline = time.time() + request.get("timeout", 20.0)
    with inbox.condition:
        while len(inbox.messages) - since < count and time.time() < deadline:
            inbox.condition.wait(0.05)
        return inbox.messages[since:]


def op_received(request):
    """How many messages the subscription to topic has received so far."""
    inbox = subscriptions[request["topic"]]
    with inbox.condition:
        return len(inbox.messages)


def publisher(request):
    topic = request["topic"]
    if topic not in publishers:
        publishers[topic] = rospy.Publisher(
            topic, message_class(request["type"]), queue_size=100, latch=request.get("latch", False)
        )
    pub = publishers[topic]
    deadline = time.time() + request.get("timeout", 20.0)
    while pub.get_num_connections() < request.get("wait_connections", 1):
        if time.time() > deadline:
            raise RuntimeError("no subscriber connected to " + topic)
        time.sleep(0.02)
    return pub


def op_publish(request):
    pub = publisher(request)
    pub.publish(fill(message_class(request["type"])(), request.get("msg", {})))
    return True


def op_stream(request):
    """Publish msg at `rate` Hz until stopped (a controller's command stream)."""
    op_stop_stream(request)
    pub = publisher(request)
    message = fill(message_class(request["type"])(), request.get("msg", {}))
    stop = threading.Event()

    def run():
        period = 1.0 / request.get("rate", 20.0)
        while not stop.is_set():
            pub.publish(message)
            stop.wait(period)

    thread = threading.Thread(target=run, daemon=True)
    thread.start()
    streams[request["topic"]] = (stop, thread)
    return True


def op_stop_stream(request):
    stream = streams.pop(request["topic"], None)
    if stream is not None:
        stream[0].set()
        stream[1].join()
    return True


def op_call(request):
    rospy.wait_for_service(request["service"], timeout=request.get("timeout", 20.0))
    proxy = rospy.ServiceProxy(request["service"], service_class(request["type"]))
    request_class = service_class(request["type"])._request_class
    response = proxy.call(fill(request_class(), request.get("request", {})))
    return to_plain(response)


def op_get_param(request):
    return rospy.get_param(request["name"])


OPS = {
    "subscribe": op_subscribe,
    "wait_connected": op_wait_connected,
    "now": op_now,
    "messages": op_messages,
    "received": op_received,
    "publish": op_publish,
    "stream": op_stream,
    "stop_stream": op_stop_stream,
    "call": op_call,
    "get_param": op_get_param,
}

rospy.init_node(sys.argv[3], disable_signals=True)
print(json.dumps({"ok": True, "result": "ready"}), flush=True)
for line in sys.stdin:
    request = json.loads(line)
    try:
        reply = {"ok": True, "result": OPS[request["op"]](request)}
    except Exception as error:
        reply = {"ok": False, "error": f"{type(error).__name__}: {error}"}
        reply["traceback"] = traceback.format_exc()
    print(json.dumps(reply), flush=True)
rospy.signal_shutdown("driver done")
