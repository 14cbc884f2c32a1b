"""`egosim report` on a bag `egosim run --record` wrote while a rospy client drove the ego
through a red light into an obstacle: the page's series are the bag's, the events are
marked where and when they happened."""

from __future__ import annotations

import base64
import io
import re
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from PIL import Image
from rosbags.rosbag1 import Reader
from rosbags.typesys import Stores, get_types_from_msg, get_typestore

from egosim.cli import main
from egosim.plots import FigureBlock, TableBlock
from egosim.report import drive_report_blocks, read_drive
from egosim.world.map import build_builtin_map
from tests.e2e.driver import RospyDriver
from tests.e2e.scenarios import OBSTACLE_AHEAD, write

pytestmark = pytest.mark.ros

EGO = ("/Ego_topic", "morai_msgs/EgoVehicleStatus")
CTRL = ("/ctrl_cmd", "morai_msgs/CtrlCmd")
SET_LIGHT = ("/SetTrafficLight", "morai_msgs/SetTrafficLight")
RED = 1
VELOCITY_MODE = 2
STOP_LINE_X = -109.5  # R1_E_1's stop line (station 146.5 from x = -256), under TL2_W
OBSTACLE_X = -55.0
RECORD_S = 14.0

# The ego starts 56.5 m before the stop line of junction 2 and drives straight on at
# 10 m/s: through the junction and into a barrier on the next block.
RED_LIGHT_AND_BARRIER = f"""\
map: town
seed: 1
ego:
  start: {{lane: R1_E_1, s: 90.0}}
  speed_mps: 10.0
obstacles:
  - {{model: Barrier, pose: {{x: {OBSTACLE_X}, y: -271.75, heading_deg: 90.0}}}}
"""


def bag_messages(bag: Path, topic: str) -> list[tuple[int, Any]]:
    """(header stamp ns, message) of `topic`, decoded by rosbags from the bag's own
    definitions (not egosim's types)."""
    store = get_typestore(Stores.EMPTY)
    with Reader(bag) as reader:
        connections = [c for c in reader.connections if c.topic == topic]
        for connection in connections:
            store.register(get_types_from_msg(connection.msgdef.data, connection.msgtype))
        rows = []
        for connection, _, raw in reader.messages(connections=connections):
            message = store.deserialize_ros1(raw, connection.msgtype)
            stamp = message.header.stamp
            rows.append((stamp.sec * 10**9 + stamp.nanosec, message))
    return sorted(rows, key=lambda row: row[0])


def test_report_of_a_recorded_drive(
    egosim: Callable[..., Any],
    rospy_client: Callable[..., RospyDriver],
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
) -> None:
    bag = tmp_path / "drive.bag"
    scenario = write(tmp_path, "red_light.yaml", RED_LIGHT_AND_BARRIER)
    simulator = egosim(
        "--scenario", str(scenario), "--map", "town", "--clock", "sim", "--rtf", "1",
        "--duration", str(RECORD_S), "--record", str(bag),
    )  # fmt: skip
    driver = rospy_client(simulator)
    driver.publish(*SET_LIGHT, {"trafficLightIndex": "TL2_W", "trafficLightStatus": RED})
    driver.stream(*CTRL, {"longlCmdType": VELOCITY_MODE, "velocity": 36.0}, rate=20)
    assert simulator.process.wait(120) == 0, simulator.process.stderr_text()

    # The bag as rosbags reads it, independently of egosim.
    ego = bag_messages(bag, EGO[0])
    bag_xy = np.array([(m.position.x, m.position.y) for _, m in ego])
    bag_speed = np.array([m.velocity.x for _, m in ego])
    assert bag_xy[:, 0].min() < STOP_LINE_X < bag_xy[:, 0].max(), "the ego crossed the line"

    drive = read_drive(bag)
    assert np.array_equal(drive.xy, bag_xy)
    assert np.array_equal(drive.speed_mps, bag_speed)
    stamps = np.array([stamp for stamp, _ in ego])
    assert np.allclose(np.diff(drive.times_s), np.diff(stamps) / 1e9)

    blocks = drive_report_blocks(drive, build_builtin_map("town"))
    figures = {b.name: b.figure for b in blocks if isinstance(b, FigureBlock)}
    (path_line, *_) = figures["trajectory"].axes[0].get_lines()
    assert np.array_equal(np.column_stack(path_line.get_data()), bag_xy)
    speed_line = figures["series"].axes[0].get_lines()[0]
    assert np.array_equal(speed_line.get_xdata(), drive.times_s)
    assert np.array_equal(speed_line.get_ydata(), bag_speed)

    # Events: the red light where the ego crossed the stop line, the barrier where it stood.
    (events,) = [b for b in blocks if isinstance(b, TableBlock)]
    kinds = [row[1] for row in events.rows]
    assert kinds.count("red_light") == 1, events.rows
    red = next(row for row in events.rows if row[1] == "red_light")
    crossing = drive.times_s[np.argmax(drive.x >= STOP_LINE_X)]
    assert red[0] == pytest.approx(crossing, abs=0.1)
    assert (red[2], red[3]) == pytest.approx((STOP_LINE_X, -271.75), abs=0.01)
    assert "TL2_W" in red[4]
    collision = next(row for row in events.rows if row[1] == "collision")
    assert collision[2] == pytest.approx(OBSTACLE_X, abs=0.5)
    assert "Barrier" in collision[4]
    # Every event marked on the time axis of every panel (the ego, still commanded forward,
    # may touch the barrier again after it stopped: each touch is a collision of its own).
    event_times = [row[0] for row in events.rows]
    for axes in figures["series"].axes:
        marked = [line.get_xdata()[0] for line in axes.get_lines()[-len(event_times) :]]
        assert marked == event_times

    # The command writes the page and its PNGs; the page embeds them.
    page = tmp_path / "out" / "report.html"
    page.parent.mkdir()
    assert main(["report", str(bag), "-o", str(page)]) == 0
    out = capsys.readouterr().out
    assert "map: town (the map egosim knows by name that the trajectory fits best" in out
    text = page.read_text()
    embedded = [base64.b64decode(d) for d in re.findall(r"base64,([^\"]+)\"", text)]
    beside = [page.with_name("report_trajectory.png"), page.with_name("report_series.png")]
    assert embedded == [p.read_bytes() for p in beside]
    for png in embedded:
        Image.open(io.BytesIO(png)).verify()
    assert "red lights run: 1" in text
    assert f"collisions: {kinds.count('collision')}" in text


def test_a_recording_begun_after_a_collision_holds_none_of_it(
    egosim: Callable[..., Any],
    rospy_client: Callable[..., RospyDriver],
    ros_env: dict[str, str],
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
) -> None:
    """`egosim record` started a while after the ego hit a barrier (nobody
    listened to /CollisionData then) must not find that collision in its first message;
    and while the ego rests against the barrier, the report tells that contact apart."""
    scenario = write(tmp_path, "obstacle.yaml", OBSTACLE_AHEAD)
    simulator = egosim(
        "--map", "straight", "--scenario", str(scenario), "--no-view",
        "--clock", "sim", "--rtf", "4",
    )  # fmt: skip
    driver = rospy_client(simulator)
    driver.subscribe(*EGO)
    driver.stream(*CTRL, {"longlCmdType": 1, "accel": 0.5}, rate=20)
    top = speed = 0.0
    seen = 0
    while not (top > 2.0 and speed < top / 2):  # the speed the barrier took away
        received = driver.messages(EGO[0], since=seen, count=1, timeout=30)
        assert received, "no /Ego_topic"
        seen += len(received)
        speed = received[-1]["velocity"]["x"]
        top = max(top, speed)
    driver.stream(*CTRL, {"longlCmdType": VELOCITY_MODE, "velocity": 0.0}, rate=20)
    settled_at_rest(driver)

    def record_and_report(name: str) -> str:
        bag = tmp_path / f"{name}.bag"
        topics = ["/Ego_topic", "/CollisionData"]
        subprocess.run(
            [
                sys.executable,
                "-m",
                "egosim",
                "record",
                str(bag),
                "--duration",
                "2",
                "--topics",
                *topics,
            ],
            env={**ros_env, "ROS_MASTER_URI": simulator.master_uri, "ROS_IP": "127.0.0.1"},
            check=True,
            capture_output=True,
            timeout=120,
        )
        page = tmp_path / f"{name}.html"
        assert main(["report", str(bag), "-o", str(page), "--map", "straight"]) == 0
        capsys.readouterr()
        first = bag_messages(bag, "/CollisionData")[0][1]
        return f"first listing: {[o.name for o in first.collision_object]}\n{page.read_text()}"

    apart = record_and_report("apart")
    assert "first listing: []" in apart  # the old collision is not brought back
    assert re.search(r"collisions: 0\s", apart)
    assert "already under way" not in apart

    # Pushed against the barrier again: the contact lasts, and every message lists it.
    driver.stream(*CTRL, {"longlCmdType": 1, "accel": 0.5}, rate=20)
    settled_at_rest(driver)
    resting = record_and_report("resting")
    assert "first listing: ['Barrier']" in resting
    assert "collisions: 0 (1 more already under way when the recording began" in resting


def settled_at_rest(driver: RospyDriver) -> None:
    """Wait until the ego has stood still for a second of simulation."""
    still_since = None
    deadline = driver.now() + 60.0
    while driver.now() < deadline:
        message = driver.next_message(EGO[0])
        now = message["header"]["stamp"]
        if abs(message["velocity"]["x"]) > 0.02:
            still_since = None
        elif still_since is None:
            still_since = now
        elif now - still_since >= 1.0:
            return
    raise AssertionError("the ego never came to rest")
