"""Count messages on topics with rospy, whatever their type (run by /usr/bin/python3).

argv: topic=count ... Subscribes to each topic with AnyMsg, prints
"subscribed" once registered, and when every topic has its count prints
{"topic": {"count": n, "type": t, "md5sum": m}} as JSON and exits.
"""

import json
import sys
import threading

import rospy

expected = dict(arg.split("=") for arg in sys.argv[1:])
received = {topic: {"count": 0, "type": None, "md5sum": None} for topic in expected}
done = threading.Event()
lock = threading.Lock()


def counter(topic):
    def on_message(message):
        with lock:
            entry = received[topic]
            entry["count"] += 1
            entry["type"] = message._connection_header["type"]
            entry["md5sum"] = message._connection_header["md5sum"]
            if all(received[t]["count"] >= int(n) for t, n in expected.items()):
                done.set()

    return on_message


rospy.init_node("replay_topic_counter", anonymous=True, disable_signals=True)
for topic in expected:
    rospy.Subscriber(topic, rospy.AnyMsg, counter(topic), queue_size=None)
print("subscribed", flush=True)
done.wait()
with lock:
    print(json.dumps(received), flush=True)
rospy.signal_shutdown("counted")
