"""An emergency-braking stack as users write them (rospy, morai_msgs): it says nothing
while the way ahead is clear, so the ego keeps the speed the scenario gave it, and
presses the brake fully once the car ahead in its lane is less than 2 s away at the
speed it closes in (`aeb`); `never` listens but never brakes.

argv: aeb | never
"""

from __future__ import annotations

import math
import sys

import rospy
from morai_msgs.msg import CtrlCmd, EgoVehicleStatus, ObjectStatusList

TTC_S = 2.0
EGO_FRONT_M = 3.65
"""The gallery's sedan: its front is 1.4 + 4.5 / 2 m ahead of the reference point."""


class Aeb:
    def __init__(self, brakes: bool) -> None:
        self.brakes = brakes
        self.ego: EgoVehicleStatus | None = None
        self.braking = False
        self.commands = rospy.Publisher("/ctrl_cmd", CtrlCmd, queue_size=1)
        rospy.Subscriber("/Ego_topic", EgoVehicleStatus, self.on_ego, queue_size=1)
        rospy.Subscriber("/Object_topic", ObjectStatusList, self.on_objects, queue_size=1)

    def on_ego(self, status: EgoVehicleStatus) -> None:
        self.ego = status
        if self.braking:
            self.commands.publish(CtrlCmd(longlCmdType=1, accel=0.0, brake=1.0))

    def on_objects(self, objects: ObjectStatusList) -> None:
        ego = self.ego
        if ego is None or self.braking or not self.brakes:
            return
        heading = math.radians(ego.heading)
        c, s = math.cos(heading), math.sin(heading)
        for car in objects.npc_list:
            dx, dy = car.position.x - ego.position.x, car.position.y - ego.position.y
            ahead, beside = dx * c + dy * s, -dx * s + dy * c
            if ahead <= 0.0 or abs(beside) > 1.5:
                continue
            gap = ahead - car.size.y / 2.0 - EGO_FRONT_M  # size: width, length, height
            closing = ego.velocity.x - car.velocity.x / 3.6  # ObjectStatus speeds: km/h
            if closing > 0.0 and gap < TTC_S * closing:
                rospy.loginfo("braking: %.1f m to the car ahead, closing at %.1f m/s", gap, closing)
                self.braking = True


if __name__ == "__main__":
    rospy.init_node("aeb_stack")
    Aeb(brakes=sys.argv[1] == "aeb")
    rospy.spin()
