"""Debian's rostopic and rosservice, given only `egosim msgs --export-python DIR` on
PYTHONPATH, read, command and call the simulator, in every release."""

from __future__ import annotations

import subprocess
from pathlib import Path

import pytest

from egosim.msgs import PROFILES
from tests.msgs.test_export import export_python

pytestmark = pytest.mark.ros

TOOL_TIMEOUT_S = 60
MAX_SPEED_READS = 20


@pytest.mark.parametrize("profile", PROFILES)
def test_ros_tools_work_with_the_exported_modules(
    egosim, ros_env: dict[str, str], tmp_path: Path, profile: str
) -> None:
    simulator = egosim("--map", "straight")
    exported = tmp_path / "morai_py"
    export_python(exported, profile)
    env = dict(
        ros_env, PYTHONPATH=str(exported), ROS_MASTER_URI=simulator.master_uri, ROS_IP="127.0.0.1"
    )

    def tool(*args: str) -> str:
        result = subprocess.run(
            list(args), env=env, capture_output=True, text=True, timeout=TOOL_TIMEOUT_S, check=False
        )
        assert result.returncode == 0, f"{args}: {result.stderr[-2000:]}"
        return result.stdout

    status = tool("rostopic", "echo", "-n", "1", "/Ego_topic")
    assert "position:" in status and "heading:" in status
    event = tool("rosservice", "call", "/Service_MoraiEventCmd", "{request: {option: 2, gear: 4}}")
    assert "gear: 4" in event
    # A command stream in the release's CtrlCmd moves the ego: the md5 matched.
    command = subprocess.Popen(
        [
            "rostopic",
            "pub",
            "-r",
            "20",
            "/ctrl_cmd",
            "morai_msgs/CtrlCmd",
            "{longlCmdType: 2, velocity: 30.0}",
        ],
        env=env,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )
    try:
        speeds = []
        for _ in range(MAX_SPEED_READS):
            speeds.append(
                float(tool("rostopic", "echo", "-n", "1", "/Ego_topic/velocity/x").split()[0])
            )
            if speeds[-1] > 1.0:
                break
    finally:
        command.terminate()
        command.wait(TOOL_TIMEOUT_S)
    assert speeds[-1] > 1.0, speeds
