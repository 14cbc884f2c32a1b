"""Recording the simulator's topics: `egosim run --record BAG` and `egosim record BAG`."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

from egosim.bridge.bindings import HANDLERS
from egosim.bridge.protocol.network import load_network_settings
from egosim.bridge.protocol.table import Direction
from egosim.bridge.sensors.camera_rows import camera_topic_names
from egosim.replay import needs_repair
from tests.conftest import EVENT_TIMEOUT_S
from tests.e2e.driver import RospyDriver
from tests.e2e.test_replay import (
    CTRL,
    EGO,
    LOAD,
    PLAY,
    PROFILE,
    STATUS,
    SUCCESS,
    read_bag,
    record_drive,
    sim_proc,
    status_after,
)
from tests.replay.test_debian_rosbag import rosbag_info

pytestmark = pytest.mark.ros

# Rows whose builders have nothing to say in a plain simulation run. (/SyncModeInfo is
# not one: any run can be switched into sync mode, so it always reports its status.)
SILENT_OUTSIDE = {"replay_info": "replay"}


def published_rows() -> dict[str, str]:
    """Topic -> type of every row egosim publishes by default (the default camera's image
    and its CameraInfo for the camera row)."""
    settings = load_network_settings(None)
    topics = {
        row.name: row.type_name
        for row in settings.enabled_rows()
        if row.direction is Direction.PUBLISH and row.key in HANDLERS.publishers
    }
    image, info = camera_topic_names(settings)
    topics[image] = settings.row("camera").type_name
    topics[info] = "sensor_msgs/CameraInfo"
    return topics


def silent_topics() -> set[str]:
    settings = load_network_settings(None)
    return {settings.row(key).name for key in SILENT_OUTSIDE}


def assert_every_header_recorded(bag: Path, from_start: bool = True) -> None:
    """Each stamped topic's header.seq runs on without a gap (from 0 when recorded from
    the start): no message published while recording is missing."""
    for topic, messages in read_bag(bag).items():
        seqs = sorted(m.header.seq for _, m in messages if hasattr(m, "header"))
        first = 0 if from_start or not seqs else seqs[0]
        assert seqs == list(range(first, first + len(seqs))), topic


def test_rosbag_info_lists_every_topic_with_its_type_and_count(
    egosim: Callable[..., Any], rospy_client: Callable[..., RospyDriver], tmp_path: Path
) -> None:
    bag = tmp_path / "drive.bag"
    record_drive(egosim, rospy_client, bag, duration=5.0, accelerate_s=0.5)
    info = rosbag_info(bag)
    assert info["indexed"] is True
    topics = {t["topic"]: t for t in info["topics"]}
    expected = {
        topic: type_name
        for topic, type_name in published_rows().items()
        if topic not in silent_topics()
    }
    expected[CTRL[0]] = CTRL[1]  # the commands egosim received
    assert {topic: t["type"] for topic, t in topics.items()} == expected
    assert {t["type"]: t["md5"] for t in info["types"]} == {
        type_name: PROFILE.message(type_name).md5sum for type_name in expected.values()
    }
    counted = {topic: len(messages) for topic, messages in read_bag(bag).items()}
    assert {topic: t["messages"] for topic, t in topics.items()} == counted
    assert_every_header_recorded(bag)
    # One /clock and one IMU message per 10 ms physics step, 50 Hz ego status.
    assert counted["/clock"] == 500
    assert counted[EGO[0]] == pytest.approx(5.0 * 50, abs=1)


def test_an_existing_bag_is_never_overwritten(tmp_path: Path) -> None:
    bag = tmp_path / "taken.bag"
    bag.write_bytes(b"precious")
    for command in (["run", "--record", str(bag)], ["record", str(bag)]):
        result = subprocess.run(
            [sys.executable, "-m", "egosim", *command],
            capture_output=True,
            text=True,
            timeout=60,
            check=False,
            env=dict(os.environ, ROS_MASTER_URI="http://127.0.0.1:9/"),
        )
        assert result.returncode == 2, command
        assert "already exists" in result.stderr.strip().splitlines()[-1], command
    assert bag.read_bytes() == b"precious"


def test_sigterm_closes_the_bag_cleanly(
    egosim: Callable[..., Any], rospy_client: Callable[..., RospyDriver], tmp_path: Path
) -> None:
    bag = tmp_path / "stopped.bag"
    simulator = egosim("--clock", "sim", "--rtf", "0", "--record", str(bag))
    client = rospy_client(simulator)
    client.subscribe(*EGO)
    client.messages(EGO[0], count=50)
    os.kill(simulator.process.popen.pid, signal.SIGTERM)
    assert simulator.process.wait() == 0
    assert not needs_repair(bag)
    assert rosbag_info(bag)["indexed"] is True
    assert_every_header_recorded(bag)


def test_a_killed_recording_keeps_what_was_written_and_replays(
    egosim: Callable[..., Any], rospy_client: Callable[..., RospyDriver], tmp_path: Path
) -> None:
    bag = tmp_path / "data" / "killed.bag"
    recording = egosim("--clock", "sim", "--rtf", "1", "--record", str(bag))
    # The recorder writes its chunks at least every second; wait for some on disk.
    deadline = time.monotonic() + EVENT_TIMEOUT_S
    while bag.stat().st_size < 200_000:
        assert time.monotonic() < deadline, "the bag never grew"
        time.sleep(0.1)
    os.killpg(recording.process.popen.pid, signal.SIGKILL)
    recording.process.wait()
    assert needs_repair(bag)
    player = egosim("--clock", "sim", "--rtf", "0")
    client = rospy_client(player)
    client.subscribe(*STATUS)
    assert sim_proc(client, replay_option=LOAD, rosbag_file_name="killed.bag")
    assert status_after(client, 0.0)["command_result"] == SUCCESS
    info = rosbag_info(bag)
    assert info["indexed"] is True
    assert {t["topic"] for t in info["topics"]} >= {EGO[0], STATUS[0]}


def test_egosim_record_against_a_running_simulator(
    egosim: Callable[..., Any],
    rospy_client: Callable[..., RospyDriver],
    spawn_ros: Callable[..., Any],
) -> None:
    simulator = egosim("--clock", "sim", "--rtf", "1")
    bag = simulator.data_root / "network.bag"
    recorder = spawn_ros(
        [sys.executable, "-m", "egosim", "record", str(bag), "--duration", "3"],
        master_uri=simulator.master_uri,
        ROS_IP="127.0.0.1",
    )
    assert recorder.wait(60) == 0, recorder.stderr_text()
    info = rosbag_info(bag)
    topics = {t["topic"]: t["type"] for t in info["topics"]}
    published = published_rows()
    assert {topic: published[topic] for topic in topics} == topics
    assert set(topics) == set(published) - silent_topics()
    assert_every_header_recorded(bag, from_start=False)

    client = rospy_client(simulator)
    client.subscribe(*STATUS)
    assert sim_proc(client, sim_process_status=PLAY, replay_option=LOAD, rosbag_file_name=bag.name)
    assert status_after(client, 0.0)["command_result"] == SUCCESS
