"""rospy subscriber printing one JSON line per message:
listener.py TOPIC TYPE [--definition F] ("*" subscribes with rospy.AnyMsg)."""

import argparse
import itertools

import rospy
from rospeer import emit, message_class, to_plain

parser = argparse.ArgumentParser()
parser.add_argument("topic")
parser.add_argument("type")
parser.add_argument("--definition")
parser.add_argument("--name", default="listener")
parser.add_argument("--tcp-nodelay", action="store_true")
args = parser.parse_args(rospy.myargv()[1:])

counter = itertools.count(1)


def on_message(message):
    header = message._connection_header
    body = to_plain(message) if args.type != "*" else {"size": len(message._buff)}
    emit(
        n=next(counter),
        msg=body,
        md5=header["md5sum"],
        type=header["type"],
        callerid=header["callerid"],
    )


rospy.init_node(args.name)
cls = message_class(args.type, args.definition)
rospy.Subscriber(args.topic, cls, on_message, tcp_nodelay=args.tcp_nodelay)
emit(event="subscribed")
rospy.spin()
