"""The camera example: an ordinary rospy node keeps the lane of the loop map from the
camera alone, through a bend."""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

import pytest

from tests.debian_ros import ROS_PYTHON
from tests.e2e.test_camera import opencv_missing

pytestmark = pytest.mark.ros

EXAMPLES = Path(__file__).parents[2] / "examples"
# 40 s at 20 km/h: the rest of the south straight and the whole east bend (radius 40 m).
DRIVE_S = "40"


def test_camera_lane_keeping_stays_in_the_lane(egosim, spawn_ros, built_msg_packages) -> None:
    if reason := opencv_missing():
        pytest.skip(reason)
    found = subprocess.run([ROS_PYTHON, "-c", "import sensor_msgs.msg"], check=False)
    if found.returncode != 0:
        pytest.skip("Debian's python3-sensor-msgs is not installed")
    simulator = egosim("--map", "loop", "--clock", "sim", "--rtf", "1")
    example = spawn_ros(
        ["python", str(EXAMPLES / "camera_lane_keeping.py"), DRIVE_S],
        master_uri=simulator.master_uri,
        ROS_IP="127.0.0.1",
        PYTHONPATH=str(built_msg_packages),
    )
    line = example.expect(r"^lane keeping done", timeout=180)
    assert example.wait(timeout=30) == 0
    frames = int(re.search(r"(\d+) frames", line.string).group(1))
    largest = float(re.search(r"centre ([\d.]+) m", line.string).group(1))
    assert frames > 300
    # Half a lane is 1.75 m; a car 1.8 m wide stays inside its lines below ~0.8 m.
    assert largest < 0.8
