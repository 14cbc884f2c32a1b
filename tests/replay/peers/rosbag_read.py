"""Read every message of a bag with Debian's rosbag Python API (run by /usr/bin/python3).

argv: bag path. Deserialises each message with classes genpy builds from the
bag's own definitions, as `rosbag play` and `rostopic echo -b` do, and prints
{"topic": [[receive_ns, md5, position_x or null], ...]} as JSON.
"""

import json
import sys

import rosbag

summary = {}
with rosbag.Bag(sys.argv[1]) as bag:
    for topic, message, received in bag.read_messages():
        position = getattr(message, "position", None)
        summary.setdefault(topic, []).append(
            [received.to_nsec(), message._md5sum, position.x if position else None]
        )
json.dump(summary, sys.stdout)
