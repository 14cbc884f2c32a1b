"""A stack node as users write them: rospy and morai_msgs imported first. Without the
exported messages on PYTHONPATH it fails at its import, as a node does on a machine where
morai_msgs was never built."""

from __future__ import annotations

import rospy
from morai_msgs.msg import CtrlCmd

if __name__ == "__main__":
    rospy.init_node("morai_node")
    rospy.Publisher("/ctrl_cmd", CtrlCmd, queue_size=1)
    rospy.spin()
