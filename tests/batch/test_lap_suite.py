"""The example suite end to end: the pure-pursuit stack (a real rospy node) through six
cases on the town, locally and on Ray actors, with the same results."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
from rosbags.rosbag1 import Reader

from tests.batch.processes import processes_using
from tests.batch.results_files import comparable

SUITE = Path(__file__).parents[2] / "examples" / "batch" / "lap_suite.yaml"
BATCH_TIMEOUT_S = 240
# A whole batch per run: beyond the default per-test timeout on a busy 2-core machine.
pytestmark = [pytest.mark.ros, pytest.mark.timeout(2 * BATCH_TIMEOUT_S)]


def run_batch(out: Path, msgs: Path, *options: str) -> subprocess.CompletedProcess[str]:
    env = {k: v for k, v in os.environ.items() if not k.startswith("ROS_")}
    env["PYTHONPATH"] = str(msgs)  # morai_msgs for the rospy stack
    return subprocess.run(
        [sys.executable, "-m", "egosim", "batch", str(SUITE), "--out", str(out), *options],
        check=False,
        env=env,
        capture_output=True,
        text=True,
        timeout=BATCH_TIMEOUT_S,
    )


@pytest.fixture(scope="module")
def local_run(
    tmp_path_factory: pytest.TempPathFactory,
    built_msg_packages: Path,
) -> tuple[Path, subprocess.CompletedProcess[str]]:
    out = tmp_path_factory.mktemp("local")
    return out, run_batch(out, built_msg_packages, "--workers", "2")


def test_the_suite_scores_every_case_and_fails_the_bad_ones(local_run) -> None:
    out, batch = local_run
    assert batch.returncode == 1, batch.stderr  # some cases fail, as they should
    document = json.loads((out / "results.json").read_text())
    cases = {c["name"]: c for c in document["cases"]}
    passing = ["lap[seed=1]", "lap[seed=2]", "speed[speed_kmh=25]", "speed[speed_kmh=40]"]
    for name in passing:
        case = cases[name]
        assert case["status"] == "passed", case
        assert case["end"] == "route_completed"
        assert case["metrics"]["route_completion"] == 1.0
        assert case["metrics"]["driving_score"] == 1.0
        assert case["metrics"]["max_lateral_error_m"] <= 0.5
    # Faster is sooner: the 50 m route at 40 km/h takes less simulated time than at 25.
    assert cases["speed[speed_kmh=40]"]["sim_time_s"] < cases["speed[speed_kmh=25]"]["sim_time_s"]

    cone = cases["cone"]
    assert cone["status"] == "failed"
    (hit,) = cone["infractions"]
    assert hit["kind"] == "collision_static"
    assert (hit["x"], hit["y"]) == pytest.approx((-46.0, -95.25))
    assert cone["metrics"]["driving_score"] == pytest.approx(0.65)

    hurried = cases["hurried"]
    assert hurried["status"] == "failed" and hurried["end"] == "time_limit"
    assert [i["kind"] for i in hurried["infractions"]] == ["timeout"]
    assert hurried["sim_time_s"] == pytest.approx(3.0)
    assert 0.1 < hurried["metrics"]["route_completion"] < 0.95

    assert document["summary"] == {
        "cases": 6,
        "passed": 4,
        "failed": 2,
        "errors": 0,
        "not_run": 0,
    }
    assert processes_using(out) == []


def test_each_case_leaves_a_bag_junit_and_a_report(local_run) -> None:
    out, _ = local_run
    document = json.loads((out / "results.json").read_text())
    for case in document["cases"]:
        with Reader(out / case["bag"]) as bag:
            topics = {c.topic for c in bag.connections}
            assert "/Ego_topic" in topics  # replays in egosim, opens in rosbag
            assert bag.message_count > 0
    suite = ET.parse(out / "junit.xml").getroot()
    assert (suite.get("tests"), suite.get("failures"), suite.get("errors")) == ("6", "2", "0")
    failed = {t.get("name") for t in suite.iter("testcase") if t.find("failure") is not None}
    assert failed == {"cone", "hurried"}
    report = (out / "report.html").read_text()
    assert "cone" in report and "hurried" in report
    assert report.count("data:image/png;base64") >= 5  # histogram, 2 x (map, timeline)


def test_ray_tasks_give_the_same_results(
    local_run,
    tmp_path: Path,
    built_msg_packages: Path,
) -> None:
    pytest.importorskip("ray", reason="Ray is an optional extra: pip install egosim[ray]")
    local_out, _ = local_run
    out = tmp_path / "ray"
    batch = run_batch(out, built_msg_packages, "--ray")
    assert batch.returncode == 1, batch.stderr
    local = json.loads((local_out / "results.json").read_text())
    on_ray = json.loads((out / "results.json").read_text())
    assert on_ray["execution"]["runner"] == "ray"
    assert comparable(on_ray) == comparable(local)
    assert processes_using(out) == []
