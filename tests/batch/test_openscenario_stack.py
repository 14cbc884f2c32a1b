"""An OpenSCENARIO batch end to end with a real rospy stack: the gallery's braking target
(Euro NCAP CCRb's situation) against an emergency-braking node that brakes in time and
one that never brakes. The ego keeps its Init speed until the node speaks; results.json
holds MORAI's evaluation verdict (the storyboard's end) next to egosim's own score."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

from tests.batch.processes import processes_using
from tests.debian_ros import ROS_PYTHON, require_ros

GALLERY = Path(__file__).parents[2] / "examples" / "openscenario"
AEB = f"{ROS_PYTHON} {Path(__file__).parent / 'peers' / 'aeb_stack.py'}"
pytestmark = pytest.mark.timeout(400)


def test_a_braking_stack_passes_the_braking_target_and_one_that_does_not_fails(
    tmp_path: Path, built_msg_packages: Path
) -> None:
    require_ros()
    suite = {
        "stack": {
            "command": "{command}",
            "env": {"PYTHONPATH": str(built_msg_packages)},
            "connect_timeout_s": 60,
        },
        # Paced, so that a node reacting over ROS sees the drive as it happens. At half
        # real time: the node must brake within about 0.6 s of simulated time of seeing
        # the car 2 s ahead, which leaves it 1.2 s of wall time to react on a machine busy
        # with other tests.
        "clock": {"mode": "sim", "rtf": 0.5},
        "time_limit_s": 20,
        "bags": "none",
        "criteria": ["no_collision"],
        "cases": [
            {
                "name": name,
                "scenario": str(GALLERY / "braking_target.xosc"),
                "parameters": {"command": f"{AEB} {mode}"},
            }
            for name, mode in (("brakes", "aeb"), ("never_brakes", "never"))
        ],
    }
    path = tmp_path / "suite.yaml"
    path.write_text(yaml.safe_dump(suite, sort_keys=False))
    out = tmp_path / "out"
    batch = subprocess.run(
        [sys.executable, "-m", "egosim", "batch", str(path), "--out", str(out)],
        capture_output=True,
        text=True,
        timeout=300,
        check=False,
    )
    assert batch.returncode == 1, batch.stderr  # one case fails, as it should
    results = {c["name"]: c for c in json.loads((out / "results.json").read_text())["cases"]}
    braked, hit = results["brakes"], results["never_brakes"]

    # The target stops 2 + 13.89/4 = 5.47 s in; the ego stands behind it 0.5 s later:
    # MORAI's success group ends the scenario there.
    assert braked["status"] == "passed", braked["reason"]
    assert braked["end"] == "scenario success"
    assert braked["scenario_outcome"]["verdict"] == "success"
    assert 5.0 < braked["scenario_outcome"]["time_s"] < 10.0
    assert braked["metrics"]["collisions"] == 0
    log = (out / braked["folder"] / "stack.log").read_text()
    assert "braking:" in log

    # Held at 50 km/h into the target that brakes at 4 m/s² from 12 m ahead: they touch
    # when 2 t² = 12 (t = 2.45 s after it brakes, 4.45 s in), the failure group's
    # collision; egosim's criterion fails on the same contact.
    assert hit["status"] == "failed"
    assert hit["end"] == "scenario failure"
    assert hit["scenario_outcome"]["verdict"] == "failure"
    assert hit["scenario_outcome"]["time_s"] == pytest.approx(4.45, abs=0.05)
    assert "the scenario's evaluation failed" in hit["reason"]
    assert "no_collision" in hit["reason"]
    assert processes_using(out) == []
