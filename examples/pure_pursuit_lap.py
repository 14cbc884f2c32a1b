#!/usr/bin/env python3
"""Drive one lap of egosim's town with a pure-pursuit controller.

An ordinary rospy node for MORAI SIM: it reads /Ego_topic, asks
/Service_MoraiVehicleSpec for the wheelbase, and sends /ctrl_cmd in velocity mode.
Run it under the ROS Python with morai_msgs on the Python path (`egosim msgs
--export-python ~/morai_py`, or a catkin workspace's devel/setup.bash):

    .venv/bin/egosim run --scenario examples/town_lap_scenario.yaml &
    PYTHONPATH=~/morai_py:$PYTHONPATH /usr/bin/python3 examples/pure_pursuit_lap.py \
        examples/town_block_lap.csv

With --sync it steps the simulator itself (MORAI's synchronous mode): one
/SyncModeWaitForTick per control period, its command sent with /SyncModeCtrlCmd
for the next frame, so the same run gives the same drive every time.

Every two seconds (of simulation time) it prints its progress (distance driven,
speed, distance from the path); once the lap is done, the largest distance from the
path it saw, and it exits.
"""

import argparse
import csv
import math

import rospy
from morai_msgs.msg import (
    CtrlCmd,
    EgoVehicleStatus,
    SyncModeCmd,
    SyncModeCtrlCmd,
    VehicleSpecIndex,
    WaitForTick,
)
from morai_msgs.srv import (
    MoraiSyncModeCmdSrv,
    MoraiSyncModeCtrlCmdSrv,
    MoraiVehicleSpecSrv,
    MoraiWaitForTickSrv,
)

LOOKAHEAD_M = 8.0
SPEED_KMH = 30.0
VELOCITY_MODE = 2
SYNC_USER = "pure_pursuit_lap"
PROGRESS_PERIOD_S = 2.0


class PurePursuitLap:
    def __init__(self, path, wheelbase, speed_kmh=SPEED_KMH):
        self.path = path
        self.wheelbase = wheelbase
        self.target_kmh = speed_kmh
        self.progress = 0  # waypoints passed, counting past the end of the lap
        self.max_off_path = 0.0
        self.off_path = 0.0
        self.driven_m = 0.0
        self.speed_kmh = 0.0
        self.last_position = None
        self.next_report_s = None
        self.done = False

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

    def command_for(self, status):
        """The CtrlCmd for this EgoVehicleStatus (a stop once the lap is done)."""
        x, y = status.position.x, status.position.y
        yaw = math.radians(status.heading)
        self.track(status)
        if self.progress >= len(self.path):
            self.done = True
            return CtrlCmd(longlCmdType=VELOCITY_MODE, velocity=0.0)
        target = self.progress
        while math.hypot(*self.offset(target, x, y)) < LOOKAHEAD_M:
            target += 1
        dx, dy = self.offset(target, x, y)
        alpha = math.atan2(dy, dx) - yaw
        steer = math.atan2(2.0 * self.wheelbase * math.sin(alpha), math.hypot(dx, dy))
        return CtrlCmd(longlCmdType=VELOCITY_MODE, velocity=self.target_kmh, front_steer=steer)

    def track(self, status):
        """Distance driven, speed and distance from the path; a progress line when due."""
        x, y = status.position.x, status.position.y
        if self.last_position is not None:
            self.driven_m += math.hypot(x - self.last_position[0], y - self.last_position[1])
        self.last_position = (x, y)
        self.speed_kmh = status.velocity.x * 3.6
        self.off_path = self.nearest_ahead(x, y)
        self.max_off_path = max(self.max_off_path, self.off_path)
        now = status.header.stamp.to_sec()
        if self.next_report_s is None:
            self.next_report_s = now + PROGRESS_PERIOD_S
        elif now >= self.next_report_s:
            print(self.progress_line(), flush=True)
            self.next_report_s += PROGRESS_PERIOD_S

    def progress_line(self):
        return (
            f"driven {self.driven_m:6.1f} m ({min(self.progress, len(self.path))}/"
            f"{len(self.path)} waypoints), speed {self.speed_kmh:4.1f} km/h, "
            f"{self.off_path:.2f} m from the path"
        )

    def offset(self, index, x, y):
        px, py = self.path[index % len(self.path)]
        return px - x, py - y


def wheelbase_of(unique_id):
    rospy.wait_for_service("/Service_MoraiVehicleSpec", timeout=30)
    spec = rospy.ServiceProxy("/Service_MoraiVehicleSpec", MoraiVehicleSpecSrv)
    return spec(VehicleSpecIndex(unique_id=unique_id)).response.wheel_base


def drive_on_topics(path, speed_kmh):
    status = rospy.wait_for_message("/Ego_topic", EgoVehicleStatus, timeout=30)
    driver = PurePursuitLap(path, wheelbase_of(status.unique_id), speed_kmh)
    command = rospy.Publisher("/ctrl_cmd", CtrlCmd, queue_size=1)

    def on_status(message):
        if not driver.done:
            command.publish(driver.command_for(message))

    rospy.Subscriber("/Ego_topic", EgoVehicleStatus, on_status, queue_size=1)
    while not driver.done and not rospy.is_shutdown():
        rospy.sleep(0.1)
    return driver


def drive_in_sync(path, speed_kmh, time_step_ms):
    for name in ("/SyncModeCmd", "/SyncModeWaitForTick", "/SyncModeCtrlCmd"):
        rospy.wait_for_service(name, timeout=30)
    start = rospy.ServiceProxy("/SyncModeCmd", MoraiSyncModeCmdSrv)
    wait_for_tick = rospy.ServiceProxy("/SyncModeWaitForTick", MoraiWaitForTickSrv)
    send = rospy.ServiceProxy("/SyncModeCtrlCmd", MoraiSyncModeCtrlCmdSrv)
    frame = start(SyncModeCmd(user_id=SYNC_USER, start_sync_mode=True, time_step=time_step_ms))
    frame = frame.response.frame
    tick = wait_for_tick(WaitForTick(user_id=SYNC_USER, frame=frame + 1)).response
    driver = PurePursuitLap(path, wheelbase_of(tick.vehicle_status.unique_id), speed_kmh)
    try:
        while not driver.done and not rospy.is_shutdown():
            command = driver.command_for(tick.vehicle_status)
            send(SyncModeCtrlCmd(frame=tick.frame + 1, command=command, sensor_capture=False))
            tick = wait_for_tick(WaitForTick(user_id=SYNC_USER, frame=tick.frame + 1)).response
    except rospy.ServiceException as error:
        # The simulator ends the drive (a time limit, a test harness): stop quietly.
        print(f"simulator stopped stepping: {error}", flush=True)
    return driver


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("path", help="CSV of x, y waypoints (m)")
    parser.add_argument("--speed-kmh", type=float, default=SPEED_KMH)
    parser.add_argument("--sync", action="store_true", help="step the simulator (sync mode)")
    parser.add_argument("--time-step-ms", type=int, default=50, help="sync mode's tick")
    args = parser.parse_args(rospy.myargv()[1:])
    with open(args.path) as file:
        path = [(float(row["x"]), float(row["y"])) for row in csv.DictReader(file)]
    rospy.init_node("pure_pursuit_lap")
    if args.sync:
        driver = drive_in_sync(path, args.speed_kmh, args.time_step_ms)
    else:
        driver = drive_on_topics(path, args.speed_kmh)
    print(
        f"lap complete: {len(path)} waypoints, largest distance from the path "
        f"{driver.max_off_path:.2f} m",
        flush=True,
    )


if __name__ == "__main__":
    main()
