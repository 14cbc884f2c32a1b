"""rospy subscriber measuring latency from the header stamp of each message (any type whose
first field is std_msgs/Header): latency_listener.py TOPIC [--idle S] [--warmup S
--duration S]. Prints one JSON summary once no message arrived for --idle seconds after the
first one, or, with --duration, once it has recorded that long (the first --warmup seconds
after the first message are not recorded)."""

import argparse
import struct
import threading
import time

import rospy
from rospeer import emit

parser = argparse.ArgumentParser()
parser.add_argument("topic")
parser.add_argument("--idle", type=float, default=1.5)
parser.add_argument("--warmup", type=float, default=0.0)
parser.add_argument("--duration", type=float, default=0.0)
args = parser.parse_args(rospy.myargv()[1:])

latencies_ns = []
arrivals = []
first_ns = []
lock = threading.Lock()
STAMP = struct.Struct("<4xII")  # Header: uint32 seq, then time stamp (secs, nsecs)


def on_message(message):
    now = time.time_ns()
    secs, nsecs = STAMP.unpack_from(message._buff)
    with lock:
        if not first_ns:
            first_ns.append(now)
        if now - first_ns[0] < args.warmup * 1e9:
            return
        latencies_ns.append(now - (secs * 1_000_000_000 + nsecs))
        arrivals.append(now)


def done():
    if not arrivals:
        return False
    now = time.time_ns()
    if args.duration:
        return now - arrivals[0] >= args.duration * 1e9
    return now - arrivals[-1] > args.idle * 1e9


rospy.init_node("latency_listener", anonymous=True)
rospy.Subscriber(args.topic, rospy.AnyMsg, on_message, tcp_nodelay=True)
emit(event="subscribed")
while not rospy.is_shutdown():
    time.sleep(0.1)
    with lock:
        if done():
            break
with lock:
    emit(latencies_ns=latencies_ns, first_ns=arrivals[0], last_ns=arrivals[-1])
