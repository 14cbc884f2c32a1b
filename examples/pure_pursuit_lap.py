#!/usr/bin/env python3
"""Drive one lap of egosim's town with a pure-pursuit controller.

An ordinary rospy node for MORAI SIM: it reads /Ego_topic, asks
/Service_MoraiVehicleSpec for the wheelbase, and sends /ctrl_cmd in velocity mode.
Run it under the ROS Python with morai_msgs on the Python path (`egosim msgs
--export-python ~/morai_py`, or a catkin workspace's devel/setup.bash):

    .venv/bin/egosim run --scenario examples/town_lap_scenario.yaml &
    PYTHONPATH=~/morai_py:$PYTHONPATH /usr/bin/python3 examples/pure_pursuit_lap.py \
        examples/town_block_lap.csv

Every two seconds it prints its progress (distance driven, speed, distance from the
path); once the lap is done, the largest distance from the path it saw, and it exits.
"""

import csv
import math
import sys

import rospy
from morai_msgs.msg import CtrlCmd, EgoVehicleStatus, VehicleSpecIndex
from morai_msgs.srv import MoraiVehicleSpecSrv

LOOKAHEAD_M = 8.0
SPEED_KMH = 30.0
VELOCITY_MODE = 2
PROGRESS_PERIOD_S = 2.0


class PurePursuitLap:
    def __init__(self, path, wheelbase):
        self.path = path
        self.wheelbase = wheelbase
        self.progress = 0  # waypoints passed, counting past the end of the lap
        self.max_off_path = 0.0
        self.off_path = 0.0
        self.driven_m = 0.0
        self.speed_kmh = 0.0
        self.last_position = None
        self.done = False
        self.command = rospy.Publisher("/ctrl_cmd", CtrlCmd, queue_size=1)

    def nearest_ahead(self, x, y):
        """Advance the progress to the nearest waypoint within the next few metres."""
        best = self.progress
        best_distance = math.inf
        for step in range(20):
            px, py = self.path[(self.progress + step) % len(self.path)]
            distance = math.hypot(px - x, py - y)
            if distance < best_distance:
                best, best_distance = self.progress + step, distance
        self.progress = best
        return best_distance

    def on_status(self, status):
        if self.done:
            return
        x, y = status.position.x, status.position.y
        yaw = math.radians(status.heading)
        if self.last_position is not None:
            self.driven_m += math.hypot(x - self.last_position[0], y - self.last_position[1])
        self.last_position = (x, y)
        self.speed_kmh = status.velocity.x * 3.6
        self.off_path = self.nearest_ahead(x, y)
        self.max_off_path = max(self.max_off_path, self.off_path)
        if self.progress >= len(self.path):
            self.done = True
            self.command.publish(CtrlCmd(longlCmdType=VELOCITY_MODE, velocity=0.0))
            return
        target = self.progress
        while math.hypot(*self.offset(target, x, y)) < LOOKAHEAD_M:
            target += 1
        dx, dy = self.offset(target, x, y)
        alpha = math.atan2(dy, dx) - yaw
        steer = math.atan2(2.0 * self.wheelbase * math.sin(alpha), math.hypot(dx, dy))
        self.command.publish(
            CtrlCmd(longlCmdType=VELOCITY_MODE, velocity=SPEED_KMH, front_steer=steer)
        )

    def progress_line(self):
        return (
            f"driven {self.driven_m:6.1f} m ({min(self.progress, len(self.path))}/"
            f"{len(self.path)} waypoints), speed {self.speed_kmh:4.1f} km/h, "
            f"{self.off_path:.2f} m from the path"
        )

    def offset(self, index, x, y):
        px, py = self.path[index % len(self.path)]
        return px - x, py - y


def main():
    with open(sys.argv[1]) as file:
        path = [(float(row["x"]), float(row["y"])) for row in csv.DictReader(file)]
    rospy.init_node("pure_pursuit_lap")
    status = rospy.wait_for_message("/Ego_topic", EgoVehicleStatus, timeout=30)
    rospy.wait_for_service("/Service_MoraiVehicleSpec", timeout=30)
    spec = rospy.ServiceProxy("/Service_MoraiVehicleSpec", MoraiVehicleSpecSrv)
    wheelbase = spec(VehicleSpecIndex(unique_id=status.unique_id)).response.wheel_base
    driver = PurePursuitLap(path, wheelbase)
    rospy.Subscriber("/Ego_topic", EgoVehicleStatus, driver.on_status, queue_size=1)
    next_report = rospy.get_time() + PROGRESS_PERIOD_S
    while not driver.done and not rospy.is_shutdown():
        rospy.sleep(0.1)
        if rospy.get_time() >= next_report:
            print(driver.progress_line(), flush=True)
            next_report += PROGRESS_PERIOD_S
    print(
        f"lap complete: {len(path)} waypoints, largest distance from the path "
        f"{driver.max_off_path:.2f} m",
        flush=True,
    )


if __name__ == "__main__":
    main()
