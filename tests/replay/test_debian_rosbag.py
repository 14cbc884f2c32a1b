"""Interop with Debian's real rosbag: it reads egosim's bags, egosim replays its bags."""

from __future__ import annotations

import json
import math
import os
import socket
import subprocess
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
import yaml

from egosim.replay import BagTimeline, repair_bag
from tests.contract import load_contract
from tests.debian_ros import ROS_PYTHON, require_ros
from tests.replay.crash import record_and_kill
from tests.replay.drive import (
    CONTROL,
    EGO,
    MOVING_OBJECTS,
    OBJECTS,
    control_velocity_kmh,
    ego_heading,
    ego_position,
    expected_counts,
    stamp,
)

pytestmark = pytest.mark.ros

PEERS = Path(__file__).parent / "peers"
ROSBAG = "/usr/bin/rosbag"
RECEIVE_DELAY_NS = 3_000_000  # the peer's messages arrive 3 ms after their stamp


def rosbag_info(path: Path) -> dict[str, Any]:
    result = subprocess.run(
        [ROSBAG, "info", "--yaml", str(path)],
        capture_output=True,
        text=True,
        check=True,
        timeout=60,
    )
    return yaml.safe_load(result.stdout)


def test_rosbag_info_lists_every_topic(recorded_drive: Path) -> None:
    require_ros()
    info = rosbag_info(recorded_drive)
    assert info["version"] == 2.0
    assert info["indexed"] is True
    topics = {t["topic"]: t for t in info["topics"]}
    assert {topic: t["messages"] for topic, t in topics.items()} == expected_counts()
    for topic, kind in (("/Ego_topic", EGO), ("/Object_topic", OBJECTS), ("/ctrl_cmd", CONTROL)):
        assert topics[topic]["type"] == kind.name
    assert {t["type"]: t["md5"] for t in info["types"]} == {
        kind.name: kind.md5sum for kind in (EGO, OBJECTS, CONTROL)
    }
    assert info["start"] == pytest.approx(stamp(0.0) / 1e9)
    assert info["messages"] == sum(expected_counts().values())


def test_rosbag_reads_every_message(recorded_drive: Path) -> None:
    """rosbag's reader deserialises each message from the bag's own definitions."""
    require_ros()
    result = subprocess.run(
        [ROS_PYTHON, str(PEERS / "rosbag_read.py"), str(recorded_drive)],
        capture_output=True,
        text=True,
        check=True,
        timeout=120,
    )
    summary = json.loads(result.stdout)
    assert {topic: len(items) for topic, items in summary.items()} == expected_counts()
    for received_ns, md5, x in summary["/Ego_topic"]:
        t = (received_ns - stamp(0.0)) / 1e9
        assert md5 == EGO.md5sum
        assert x == pytest.approx(ego_position(t)[0], abs=1e-9)


def test_rosbag_reads_a_repaired_bag(tmp_path: Path) -> None:
    require_ros()
    bag = tmp_path / "killed.bag"
    stats = record_and_kill(bag, 1500, 16 * 1024, flush_interval=3600.0)
    repair_bag(bag)
    info = rosbag_info(bag)
    assert info["indexed"] is True
    assert info["messages"] == stats["flushed"]
    assert [(t["topic"], t["type"]) for t in info["topics"]] == [("/Ego_topic", EGO.name)]


@pytest.fixture
def ros_master(tmp_path: Path) -> Iterator[dict[str, str]]:
    """A private rosmaster; the environment that points ROS tools at it."""
    require_ros()
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        port = probe.getsockname()[1]
    env = {
        **os.environ,
        "ROS_MASTER_URI": f"http://127.0.0.1:{port}/",
        "ROS_HOSTNAME": "127.0.0.1",
        "ROS_HOME": str(tmp_path / "ros_home"),
    }
    master = subprocess.Popen(
        ["/usr/bin/rosmaster", "--core", "-p", str(port)],
        env=env,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )
    try:
        yield env
    finally:
        master.terminate()
        master.wait(timeout=30)


def test_rosbag_play_publishes_every_message(
    recorded_drive: Path, ros_master: dict[str, str]
) -> None:
    """`rosbag play` republishes the bag; a rospy node receives every message with its type."""
    counts = expected_counts()
    counter = subprocess.Popen(
        [ROS_PYTHON, str(PEERS / "topic_counter.py"), *(f"{t}={n}" for t, n in counts.items())],
        env=ros_master,
        stdout=subprocess.PIPE,
        text=True,
    )
    try:
        assert counter.stdout is not None
        lines = iter(counter.stdout)  # rospy also prints while it waits for the master
        assert "subscribed" in (line.strip() for line in lines)
        subprocess.run(
            [
                ROSBAG,
                "play",
                "--wait-for-subscribers",
                "--rate=10",
                "--queue=10000",
                str(recorded_drive),
            ],
            env=ros_master,
            capture_output=True,
            check=True,
            timeout=120,
        )
        received = json.loads(next(line for line in lines if line.startswith("{")))
    finally:
        counter.kill()
        counter.wait()
    for topic, kind in (("/Ego_topic", EGO), ("/Object_topic", OBJECTS), ("/ctrl_cmd", CONTROL)):
        assert received[topic] == {"count": counts[topic], "type": kind.name, "md5sum": kind.md5sum}


def vector(x: float, y: float, z: float = 0.0) -> dict[str, float]:
    return {"x": x, "y": y, "z": z}


def header(t: float, seq: int) -> dict[str, Any]:
    secs, nsecs = divmod(stamp(t), 10**9)
    return {"seq": seq, "stamp": {"secs": secs, "nsecs": nsecs}, "frame_id": "map"}


def peer_messages() -> list[dict[str, Any]]:
    """Two seconds of the drive, as plain values for genpy."""
    messages = []
    for k in range(101):
        t = k / 50
        values = {
            "header": header(t, k),
            "unique_id": -1,
            "position": vector(*ego_position(t)[:2]),
            "velocity": vector(10.0, 0.0),
            "heading": math.degrees(ego_heading(t)),
            "accel": 0.5,
        }
        messages.append(
            {
                "topic": "/Ego_topic",
                "type": EGO.name,
                "receive_ns": stamp(t) + RECEIVE_DELAY_NS,
                "values": values,
            }
        )
    for k in range(41):
        t = k / 20
        npcs = [
            {
                "unique_id": obj.unique_id,
                "type": obj.type_code,
                "name": f"object#{obj.unique_id}",
                "heading": obj.heading_deg(),
                "velocity": vector(obj.velocity[0] * 3.6, obj.velocity[1] * 3.6),
                "size": vector(1.8, 4.5, 1.5),
                "position": vector(*obj.position(t)[:2]),
            }
            for obj in MOVING_OBJECTS
            if obj.list_name == "npc_list"
        ]
        values = {"header": header(t, k), "num_of_npcs": len(npcs), "npc_list": npcs}
        messages.append(
            {
                "topic": "/Object_topic",
                "type": OBJECTS.name,
                "receive_ns": stamp(t) + RECEIVE_DELAY_NS,
                "values": values,
            }
        )
    for k in range(21):
        t = k / 10
        values = {"longlCmdType": 2, "velocity": control_velocity_kmh(t)}
        messages.append(
            {
                "topic": "/ctrl_cmd",
                "type": CONTROL.name,
                "receive_ns": stamp(t) + RECEIVE_DELAY_NS,
                "values": values,
            }
        )
    return messages


def test_bag_written_by_rosbag_replays(tmp_path: Path) -> None:
    require_ros()
    contract = load_contract("26.r1")["messages"]
    bag = tmp_path / "rosbag_api.bag"
    request = {
        "path": str(bag),
        "definitions": {
            name: contract[name]["definition"] for name in (EGO.name, OBJECTS.name, CONTROL.name)
        },
        "messages": peer_messages(),
    }
    subprocess.run(
        [ROS_PYTHON, str(PEERS / "rosbag_write.py")],
        input=json.dumps(request),
        capture_output=True,
        text=True,
        check=True,
        timeout=120,
    )
    timeline = BagTimeline.open(bag)
    assert timeline.profile == "26.r1"
    # Header stamps are the time base; the 3 ms receive delay does not shift the drive.
    assert timeline.start_ns == stamp(0.0)
    assert timeline.duration == pytest.approx(2.0)
    for t in (0.0, 0.5, 1.01, 1.337, 2.0):
        frame = timeline.sample(t)
        assert frame.ego is not None
        assert math.dist(frame.ego.position, ego_position(t)) < 0.01
        for obj in frame.npcs:
            moving = next(m for m in MOVING_OBJECTS if m.unique_id == obj.unique_id)
            assert math.dist(obj.position, moving.position(t)) < 0.01
        assert len(frame.npcs) == 3
    control = timeline.sample(1.35).control
    assert control is not None
    # CtrlCmd has no header: placed by receive time minus the measured 3 ms delay.
    assert control.velocity == pytest.approx(control_velocity_kmh(1.3) / 3.6)
    assert timeline.control is not None
    assert timeline.control.times[1] == pytest.approx(0.1)
