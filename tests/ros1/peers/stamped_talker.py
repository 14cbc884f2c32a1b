"""rospy publisher stamping header.stamp with the wall time of each publish:
stamped_talker.py TOPIC TYPE DEFINITION_FILE --rate HZ (0: flat out) --duration S
[--cloud-bytes N] (fills a PointCloud2 with N bytes of data)."""

import argparse
import time

import rospy
from rospeer import emit, message_class

parser = argparse.ArgumentParser()
parser.add_argument("topic")
parser.add_argument("type")
parser.add_argument("definition")
parser.add_argument("--rate", type=float, default=100.0)
parser.add_argument("--duration", type=float, default=5.0)
parser.add_argument("--cloud-bytes", type=int, default=0)
args = parser.parse_args(rospy.myargv()[1:])

rospy.init_node("stamped_talker", anonymous=True)
cls = message_class(args.type, args.definition)
pub = rospy.Publisher(args.topic, cls, queue_size=100)
message = cls()
if args.cloud_bytes:
    message.height, message.point_step = 1, 16
    message.width = args.cloud_bytes // message.point_step
    message.row_step = message.width * message.point_step
    message.data = bytes(message.row_step)
while pub.get_num_connections() < 1:
    time.sleep(0.01)
time.sleep(0.5)
emit(event="publishing")
period = 1.0 / args.rate if args.rate else 0.0
start = time.perf_counter()
sent = 0
while time.perf_counter() - start < args.duration:
    message.header.seq = sent
    now_ns = time.time_ns()
    message.header.stamp = rospy.Time(now_ns // 1_000_000_000, now_ns % 1_000_000_000)
    pub.publish(message)
    sent += 1
    if period:
        delay = start + sent * period - time.perf_counter()
        if delay > 0:
            time.sleep(delay)
emit(event="done", sent=sent)
time.sleep(3)
