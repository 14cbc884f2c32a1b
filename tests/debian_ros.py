"""Debian's ROS 1 (Noetic) test peers: where they are and how to skip without them."""

from __future__ import annotations

import shutil
import subprocess
from functools import cache

import pytest

# Debian installs rospy & co. for its own interpreter, not for the venv's.
ROS_PYTHON = "/usr/bin/python3"


@cache
def missing_ros_reason() -> str | None:
    """Why Debian's ROS 1 peers cannot run here, or None when they can."""
    if not shutil.which(ROS_PYTHON):
        return f"{ROS_PYTHON} not found"
    probe = subprocess.run(
        [ROS_PYTHON, "-c", "import rospy, genpy, rosbag, rosmaster"],
        capture_output=True,
        text=True,
        check=False,
    )
    if probe.returncode != 0:
        error = probe.stderr.strip().splitlines()[-1:] or [f"status {probe.returncode}"]
        return (
            "Debian's ROS 1 peers are not installed (apt-get install python3-rospy "
            "python3-rosmaster python3-rostopic python3-rosservice python3-rosbag "
            f"python3-genpy ros-core-dev): {error[0]}"
        )
    return None


def require_ros() -> None:
    """Skip the calling test, loudly, when the real ROS 1 is absent."""
    if reason := missing_ros_reason():
        pytest.skip(reason)
