"""A rospy node that listens to /egosim/markers with Debian's visualization_msgs class, as
RViz's MarkerArray display would, and prints what it got as one JSON line per message.

Run by /usr/bin/python3. argv: TOPIC COUNT TIMEOUT_S. Exits after COUNT messages (or the
timeout, printing what it has).
"""

import json
import sys
import threading

import rospy
from visualization_msgs.msg import MarkerArray


def summary(message):
    return [
        {
            "ns": m.ns,
            "id": m.id,
            "type": m.type,
            "action": m.action,
            "frame_id": m.header.frame_id,
            "stamp": m.header.stamp.to_sec(),
            "position": [m.pose.position.x, m.pose.position.y, m.pose.position.z],
            "orientation": [
                m.pose.orientation.x,
                m.pose.orientation.y,
                m.pose.orientation.z,
                m.pose.orientation.w,
            ],
            "scale": [m.scale.x, m.scale.y, m.scale.z],
            "color": [m.color.r, m.color.g, m.color.b, m.color.a],
            "lifetime": m.lifetime.to_sec(),
            "points": [[p.x, p.y, p.z] for p in m.points] if m.type in (7, 9) else len(m.points),
            "colors": [[c.r, c.g, c.b, c.a] for c in m.colors],
            "text": m.text,
        }
        for m in message.markers
    ]


def main():
    topic, count, timeout = sys.argv[1], int(sys.argv[2]), float(sys.argv[3])
    got = []
    done = threading.Event()

    def received(message):
        if len(got) < count:
            header = getattr(message, "_connection_header", {}) or {}
            got.append({"latching": header.get("latching"), "markers": summary(message)})
        if len(got) >= count:
            done.set()

    rospy.init_node("marker_listener", anonymous=True, disable_signals=True)
    rospy.Subscriber(topic, MarkerArray, received, queue_size=100)
    done.wait(timeout)
    for message in got[:count]:
        sys.stdout.write(json.dumps(message) + "\n")
    sys.stdout.flush()
    rospy.signal_shutdown("done")


if __name__ == "__main__":
    main()
