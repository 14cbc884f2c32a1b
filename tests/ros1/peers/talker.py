"""rospy publisher: talker.py TOPIC TYPE [--definition F] [--fields JSON] [--rate HZ]
[--count N] [--latch] [--wait-subscribers N]. std_msgs/String messages say "hello <i>"."""

import argparse
import json
import time

import rospy
from rospeer import emit, fill, message_class

parser = argparse.ArgumentParser()
parser.add_argument("topic")
parser.add_argument("type")
parser.add_argument("--definition")
parser.add_argument("--fields", default="{}")
parser.add_argument("--rate", type=float, default=20.0)
parser.add_argument("--count", type=int, default=0, help="0: until killed")
parser.add_argument("--latch", action="store_true")
parser.add_argument("--wait-subscribers", type=int, default=0)
parser.add_argument("--name", default="talker")
args = parser.parse_args(rospy.myargv()[1:])

rospy.init_node(args.name)
cls = message_class(args.type, args.definition)
pub = rospy.Publisher(args.topic, cls, queue_size=100, latch=args.latch)
while pub.get_num_connections() < args.wait_subscribers and not rospy.is_shutdown():
    time.sleep(0.01)
emit(event="ready")
rate = rospy.Rate(args.rate)
i = 0
while not rospy.is_shutdown() and (args.count == 0 or i < args.count):
    message = fill(cls(), json.loads(args.fields))
    if args.type == "std_msgs/String":
        message.data = f"hello {i}"
    pub.publish(message)
    i += 1
    rate.sleep()
emit(event="done", count=i)
if args.count:
    rospy.spin()
