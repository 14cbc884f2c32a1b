"""The user-facing example: an ordinary rospy node drives a lap of the town."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

pytestmark = pytest.mark.ros

EXAMPLES = Path(__file__).parents[2] / "examples"


def test_pure_pursuit_example_completes_a_lap(egosim, spawn_ros, built_msg_packages) -> None:
    scenario = str(EXAMPLES / "town_lap_scenario.yaml")
    simulator = egosim("--scenario", scenario, "--clock", "sim", "--rtf", "4")
    example = spawn_ros(
        ["python", str(EXAMPLES / "pure_pursuit_lap.py"), str(EXAMPLES / "town_block_lap.csv")],
        master_uri=simulator.master_uri,
        ROS_IP="127.0.0.1",
        PYTHONPATH=str(built_msg_packages),
    )
    # It reports its progress while it drives, not only at the end.
    progress = example.expect(r"^driven +([\d.]+) m .* speed +([\d.]+) km/h", timeout=180)
    assert float(progress.group(1)) > 0.0
    line = example.expect(r"^lap complete", timeout=180)
    assert example.wait(timeout=30) == 0
    largest = float(re.search(r"path ([\d.]+) m", line.string).group(1))
    assert largest < 2.0
