"""What `egosim run` tells its console: the drive's events at INFO (a red light run, a
collision with whom and where, a control-mode change), the routine comings and goings of
ROS tools below it (a `rostopic echo` that has its messages and leaves)."""

from __future__ import annotations

import re
import subprocess
import time
from pathlib import Path

import pytest

from egosim.world.map import build_builtin_map
from tests.e2e import scenarios
from tests.waiting import until

pytestmark = pytest.mark.ros

CTRL = ("/ctrl_cmd", "morai_msgs/CtrlCmd")
EVENT = ("/Service_MoraiEventCmd", "morai_msgs/MoraiEventCmdSrv")
SET_LIGHT = ("/SetTrafficLight", "morai_msgs/SetTrafficLight")
OPTION_CTRL_MODE = 1
KEYBOARD, EXTERNAL = 1, 3
RED = 1
TOOL_TIMEOUT_S = 60
# The town's R1_E_1 ends at a light; a barrier stands 19.5 m past its stop line.
RED_THEN_BARRIER = """\
map: town
seed: 1
ego:
  start: {lane: R1_E_1, s: 126.5}
obstacles:
  - {model: Barrier, pose: {x: -90.0, y: -271.75, heading_deg: 90.0}}
"""
LINE = re.compile(r"^\S+ \S+ (?P<level>[A-Z]+) (?P<logger>\S+): (?P<message>.*)$")


def log_lines(stderr: str) -> list[tuple[str, str, str]]:
    """(level, logger, message) of each line egosim logged."""
    return [
        (match["level"], match["logger"], match["message"])
        for line in stderr.splitlines()
        if (match := LINE.match(line))
    ]


def test_the_console_tells_the_drive_and_not_the_tools_that_leave(
    egosim, rospy_client, ros_env: dict[str, str], built_msg_packages: Path, tmp_path: Path
) -> None:
    data_root = tmp_path / "data"  # the simulator's (see the egosim fixture)
    data_root.mkdir()
    scenario = scenarios.write(data_root, "red_then_barrier.yaml", RED_THEN_BARRIER)
    simulator = egosim("--scenario", str(scenario), "--no-view", "--log-level", "DEBUG")
    lane = build_builtin_map("town").lanes["R1_E_1"]
    assert lane.traffic_light_ids and lane.stop_line_s is not None

    # A real rostopic echo takes three statuses and leaves.
    env = dict(
        ros_env,
        PYTHONPATH=str(built_msg_packages),
        ROS_MASTER_URI=simulator.master_uri,
        ROS_IP="127.0.0.1",
    )
    echo = subprocess.run(
        ["rostopic", "echo", "-n", "3", "/Ego_topic"],
        env=env,
        capture_output=True,
        text=True,
        timeout=TOOL_TIMEOUT_S,
        check=False,
    )
    assert echo.returncode == 0, echo.stderr[-2000:]

    client = rospy_client(simulator)
    for mode in (KEYBOARD, EXTERNAL):
        request = {"request": {"option": OPTION_CTRL_MODE, "ctrl_mode": mode, "gear": -1}}
        client.call(*EVENT, request)
    client.publish(
        *SET_LIGHT, {"trafficLightIndex": lane.traffic_light_ids[0], "trafficLightStatus": RED}
    )
    client.stream(*CTRL, {"longlCmdType": 1, "accel": 0.5}, rate=20)

    def collision_logged() -> list[tuple[str, str, str]] | None:
        lines = log_lines(simulator.process.stderr_text())
        if any("collision" in message for _, _, message in lines):
            return lines
        time.sleep(0.2)
        return None

    lines = until(collision_logged, "a collision on the console", timeout_s=60.0)
    client.stop_stream(CTRL[0])
    info = [(logger, message) for level, logger, message in lines if level != "DEBUG"]
    drive = [message for logger, message in info if logger == "egosim.drive"]
    assert len(drive) == 2, info
    red, collision = drive
    x, y, _, _ = build_builtin_map("town").pose_at(lane.id, lane.stop_line_s)
    assert red.startswith(
        f"ego 1: red light run: light {lane.traffic_light_ids[0]} red at the stop line of lane "
        f"{lane.id} at ({x:.1f}, {y:.1f}) m, t "
    ), red
    assert re.match(
        r"ego 1: collision \(obstacle\) with Barrier \(id \d+\) at \(-90\.0, -271\.8\) m, t ",
        collision,
    ), collision
    assert (
        "egosim.bridge.ego_session",
        "ego 1: control mode external -> keyboard (/Service_MoraiEventCmd)",
    ) in info
    assert (
        "egosim.bridge.ego_session",
        "ego 1: control mode keyboard -> external (/Service_MoraiEventCmd)",
    ) in info

    # The echo's departure was seen, at DEBUG only: no INFO line about it.
    departures = [
        message
        for level, logger, message in lines
        if level == "DEBUG" and logger == "egosim.ros1.publication" and "/rostopic_" in message
    ]
    assert departures and all(" left: " in message for message in departures), lines
    assert not [message for _, message in info if "rostopic" in message or "left" in message], info
    assert not [message for _, message in info if "Broken pipe" in message or "reset" in message]
