"""Ctrl-C (SIGINT to `egosim batch`) keeps the drive of every running case, locally and as
Ray tasks alike: the two runs' results.json are the same case by case. The stacks step
the world in sync mode for 50 ticks and then wait, one leaving on SIGINT, one deaf to it
(stopped with SIGKILL), so each drive is as long whenever the run is stopped."""

from __future__ import annotations

import signal
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

import pytest
import yaml

from tests.batch.processes import processes_using
from tests.batch.results_files import comparable, read_results
from tests.batch.suites import STRAIGHT_SCENARIO
from tests.waiting import until

STEPPING = f"{sys.executable} {Path(__file__).parent / 'peers' / 'stepping_stack.py'}"
FRAMES = 50
BATCH_TIMEOUT_S = 120
pytestmark = pytest.mark.timeout(3 * BATCH_TIMEOUT_S)


def write_suite(folder: Path) -> Path:
    folder.mkdir()
    (folder / "straight.yaml").write_text(yaml.safe_dump(STRAIGHT_SCENARIO))
    cases = [
        {"name": name, "scenario": "straight.yaml", "parameters": {"then": then}}
        for name, then in (("leaves_on_sigint", "idle"), ("deaf_to_sigint", "hang"))
    ]
    suite = {
        "stack": {"command": f"{STEPPING} --frames {FRAMES} {{then}}"},
        "clock": "sync",
        "time_limit_s": 60,
        "cases": cases,
    }
    path = folder / "suite.yaml"
    path.write_text(yaml.safe_dump(suite, sort_keys=False))
    return path


def interrupted_run(suite: Path, out: Path, *options: str) -> dict[str, Any]:
    """Run the suite, SIGINT the batch once every case's stack has stepped its ticks; the
    results it wrote."""
    batch = subprocess.Popen(
        [sys.executable, "-m", "egosim", "batch", str(suite), "--out", str(out), *options],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:

        def every_stack_stepped() -> bool:
            time.sleep(0.2)
            return len(list(out.glob("*/stepped"))) == 2 or batch.poll() is not None

        until(every_stack_stepped, "both stacks to step their ticks", 90.0)
        assert batch.poll() is None, batch.communicate()
        batch.send_signal(signal.SIGINT)
        _, stderr = batch.communicate(timeout=BATCH_TIMEOUT_S)
    finally:
        if batch.poll() is None:
            batch.kill()
            batch.communicate()
    assert batch.returncode == 130, stderr
    assert processes_using(out) == []
    return read_results(out)


@pytest.fixture(scope="module")
def suite(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return write_suite(tmp_path_factory.mktemp("suite") / "suite")


@pytest.fixture(scope="module")
def local(suite: Path, tmp_path_factory: pytest.TempPathFactory) -> dict[str, Any]:
    return interrupted_run(suite, tmp_path_factory.mktemp("local"), "--workers", "2")


@pytest.fixture(scope="module")
def on_ray(suite: Path, tmp_path_factory: pytest.TempPathFactory) -> dict[str, Any]:
    pytest.importorskip("ray", reason="Ray is an optional extra: pip install egosim[ray]")
    return interrupted_run(suite, tmp_path_factory.mktemp("ray"), "--ray")


@pytest.mark.parametrize("runner", ["local", "on_ray"])
def test_each_running_case_keeps_its_drive(runner: str, request: pytest.FixtureRequest) -> None:
    document = request.getfixturevalue(runner)
    assert document["execution"]["interrupted"] is True
    for case in document["cases"]:
        assert (case["status"], case["reason"], case["end"]) == ("error", "interrupted", "stopped")
        assert case["sim_time_s"] == pytest.approx((FRAMES - 1) * 0.01)  # from tick 1
        assert case["metrics"]["driving_score"] == 1.0
        assert case["bag"] is not None


def test_an_interrupted_ray_run_gives_the_same_results(local, on_ray) -> None:
    assert comparable(on_ray) == comparable(local)
