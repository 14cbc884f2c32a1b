"""A MORAI lane-keeping client sees its lane in /image_jpeg/compressed (rospy + OpenCV)."""

from __future__ import annotations

import json
import subprocess
from pathlib import Path

import pytest

from egosim.msgs import get_profile
from egosim.sensors.camera import DEFAULT_CAMERA_MOUNT
from egosim.world.vehicle import DEFAULT_EGO_MODEL, sensor_mount_origin, vehicle_model
from tests.debian_ros import ROS_PYTHON
from tests.e2e.test_sync_mode import CTRL, start_sync_mode, tick

pytestmark = pytest.mark.ros

PEER = Path(__file__).parent / "peers" / "camera_lane_client.py"
LANE_WIDTH_M = 3.5
CLIENT_TIMEOUT_S = 120


def opencv_missing() -> str | None:
    found = subprocess.run([ROS_PYTHON, "-c", "import cv2"], capture_output=True, check=False)
    return None if found.returncode == 0 else "Debian's python3-opencv is not installed"


def test_an_opencv_client_finds_both_lines_of_the_ego_lane(egosim, ros_env, tmp_path) -> None:
    if reason := opencv_missing():
        pytest.skip(reason)
    simulator = egosim("--map", "straight")
    definition = tmp_path / "CompressedImage.msg"
    definition.write_text(get_profile("26.r1").message("sensor_msgs/CompressedImage").definition)
    # MORAI's mounts start at wheel-centre height: the camera stands this high above the road.
    height = DEFAULT_CAMERA_MOUNT.z + sensor_mount_origin(vehicle_model(DEFAULT_EGO_MODEL))[2]
    env = dict(ros_env, ROS_MASTER_URI=simulator.master_uri, ROS_IP="127.0.0.1")
    client = subprocess.run(
        [ROS_PYTHON, str(PEER), "/image_jpeg/compressed", str(definition), str(height)],
        env=env,
        capture_output=True,
        text=True,
        timeout=CLIENT_TIMEOUT_S,
        check=False,
    )
    assert client.returncode == 0, client.stderr[-3000:]
    seen = json.loads(client.stdout.strip().splitlines()[-1])
    assert seen["format"] == "jpeg"
    assert seen["frame_id"] == "Camera"
    assert seen["size"] == [640, 480]
    # The ego starts on the straight map's inner lane: the yellow centre line half a
    # lane to its left, the white dashed line half a lane to its right.
    assert seen["left_pixels"] > 50 and seen["right_pixels"] > 50
    assert seen["left_m"] == pytest.approx(LANE_WIDTH_M / 2, abs=0.25)
    assert seen["right_m"] == pytest.approx(-LANE_WIDTH_M / 2, abs=0.25)


def test_sync_mode_renders_only_the_frames_a_client_captures(egosim, rospy_client) -> None:
    client = rospy_client(egosim("--map", "straight", "--clock", "sync"))
    topic = "/image_jpeg/compressed"
    client.subscribe(topic, "sensor_msgs/CompressedImage", raw=True)
    client.wait_connected(topic)
    first = start_sync_mode(client)
    assert tick(client, first + 3)["tick_status"] is True
    capture = {"frame": first + 5, "command": {"longlCmdType": 2}, "sensor_capture": True}
    assert client.call(*CTRL, {"request": capture})["response"]["result"] is True
    assert tick(client, first + 8)["tick_status"] is True
    frames = client.messages(topic, count=1, timeout=20)
    # Nothing for the other ticks: exactly one frame arrives, a JPEG.
    assert len(client.messages(topic, count=2, timeout=2)) == 1
    assert bytes.fromhex(frames[0]["hex"])[-2:] == b"\xff\xd9"
