"""Ctrl-C (SIGINT to `egosim batch`) and SIGTERM (a cancelled CI job, `timeout`) keep the
drive of every running case, locally and on Ray alike: the runs' results.json are the same
case by case, and nothing is left running. SIGINT stops a batch started as a script's
background job too (which has SIGINT ignored). The stacks step the world in sync mode for 50
ticks and then wait, one leaving on SIGINT, one deaf to it (stopped with SIGKILL), so each
drive is as long whenever the run is stopped. A second signal stops a batch at once."""

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
STACKS = (("leaves_on_sigint", "idle"), ("deaf_to_sigint", "hang"))
pytestmark = pytest.mark.timeout(3 * BATCH_TIMEOUT_S)


def write_suite(folder: Path, stacks: tuple[tuple[str, str], ...] = STACKS) -> Path:
    folder.mkdir()
    (folder / "straight.yaml").write_text(yaml.safe_dump(STRAIGHT_SCENARIO))
    cases = [
        {"name": name, "scenario": "straight.yaml", "parameters": {"then": then}}
        for name, then in stacks
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


BACKGROUND_JOB = ["/bin/sh", "-c", 'trap "" INT; exec "$@"', "sh"]
"""Runs a command as a shell runs a script's background job: with SIGINT ignored."""


def interrupted_run(
    suite: Path,
    out: Path,
    *options: str,
    number: int = signal.SIGINT,
    as_background_job: bool = False,
    again_once: str | None = None,
) -> dict[str, Any]:
    """Run the suite, send the batch signal `number` once every case's stack has stepped
    its ticks (and again once the file `again_once` is in a case folder); the results it
    wrote."""
    command = [sys.executable, "-m", "egosim", "batch", str(suite), "--out", str(out), *options]
    batch = subprocess.Popen(
        (BACKGROUND_JOB if as_background_job else []) + command,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    stacks = len(yaml.safe_load(suite.read_text())["cases"])
    try:

        def every_stack_stepped() -> bool:
            time.sleep(0.2)
            return len(list(out.glob("*/stepped"))) == stacks or batch.poll() is not None

        until(every_stack_stepped, "every stack to step its ticks", 90.0)
        assert batch.poll() is None, batch.communicate()
        batch.send_signal(number)
        if again_once is not None:
            until(lambda: any(out.glob(f"*/{again_once}")), f"{again_once} in a case", 30.0)
            batch.send_signal(number)
        _, stderr = batch.communicate(timeout=BATCH_TIMEOUT_S)
    finally:
        if batch.poll() is None:
            batch.kill()
            batch.communicate()
    assert batch.returncode == 128 + number, stderr
    assert processes_using(out) == []
    assert (out / "junit.xml").exists()
    # A second signal does not wait for the report.
    assert (out / "report.html").exists() is (again_once is None)
    return read_results(out)


@pytest.fixture(scope="module")
def suite(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return write_suite(tmp_path_factory.mktemp("suite") / "suite")


@pytest.fixture(scope="module")
def local(suite: Path, tmp_path_factory: pytest.TempPathFactory) -> dict[str, Any]:
    out = tmp_path_factory.mktemp("local")
    return interrupted_run(suite, out, "--workers", "2", as_background_job=True)


@pytest.fixture(scope="module")
def local_sigterm(suite: Path, tmp_path_factory: pytest.TempPathFactory) -> dict[str, Any]:
    out = tmp_path_factory.mktemp("local_sigterm")
    return interrupted_run(suite, out, "--workers", "2", number=signal.SIGTERM)


@pytest.fixture(scope="module")
def on_ray(suite: Path, tmp_path_factory: pytest.TempPathFactory) -> dict[str, Any]:
    pytest.importorskip("ray", reason="Ray is an optional extra: pip install egosim[ray]")
    return interrupted_run(suite, tmp_path_factory.mktemp("ray"), "--ray")


@pytest.fixture(scope="module")
def ray_sigterm(suite: Path, tmp_path_factory: pytest.TempPathFactory) -> dict[str, Any]:
    pytest.importorskip("ray", reason="Ray is an optional extra: pip install egosim[ray]")
    out = tmp_path_factory.mktemp("ray_sigterm")
    return interrupted_run(suite, out, "--ray", number=signal.SIGTERM)


RUNS = ["local", "local_sigterm", "on_ray", "ray_sigterm"]


@pytest.mark.parametrize("runner", RUNS)
def test_each_running_case_keeps_its_drive(runner: str, request: pytest.FixtureRequest) -> None:
    document = request.getfixturevalue(runner)
    assert document["execution"]["interrupted"] is True
    for case in document["cases"]:
        assert (case["status"], case["reason"], case["end"]) == ("error", "interrupted", "stopped")
        assert case["sim_time_s"] == pytest.approx(FRAMES * 0.01)
        assert case["metrics"]["driving_score"] == 1.0
        assert case["bag"] is not None


@pytest.mark.parametrize("runner", RUNS[1:])
def test_an_interrupted_run_gives_the_same_results(
    runner: str, local: dict[str, Any], request: pytest.FixtureRequest
) -> None:
    assert comparable(request.getfixturevalue(runner)) == comparable(local)


def test_a_second_signal_stops_at_once(tmp_path: Path) -> None:
    # The deaf stack would have 5 s to end after the first signal: the second kills it,
    # and its simulator, at once.
    suite = write_suite(tmp_path / "suite", (("deaf_to_sigint", "hang"),))
    out = tmp_path / "out"
    document = interrupted_run(suite, out, number=signal.SIGTERM, again_once="sigint")
    (case,) = document["cases"]
    assert (case["status"], case["reason"]) == ("error", "interrupted")
    assert case["metrics"] is None  # killed before it could score the drive
