"""What Debian's `rosmsg show` / `rossrv show` print for each named type, as JSON.

argv: TYPE... (`msg:pkg/Name` or `srv:pkg/Name`); packages found through ROS_PACKAGE_PATH.
"""

import json
import sys

import rosmsg
import rospkg

rospack = rospkg.RosPack()
shown = {}
for arg in sys.argv[1:]:
    kind, name = arg.split(":", 1)
    get_text = rosmsg.get_msg_text if kind == "msg" else rosmsg.get_srv_text
    shown[name] = get_text(name, raw=False, rospack=rospack)
print(json.dumps(shown))
