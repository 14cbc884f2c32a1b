"""`egosim batch` starts its simulator workers as it begins, before it loads the suite:
those no case needs (fewer cases than workers, a suite that does not load) end at once,
and none outlives the batch."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from egosim.app.exit_codes import EXIT_BAD_INPUT
from egosim.batch.case import CaseSpec
from egosim.batch.early_workers import default_workers
from egosim.batch.errors import SuiteError
from egosim.batch.suite import load_suite
from egosim.cli import batch_run, main
from tests.batch.processes import processes_using
from tests.batch.results_files import read_results
from tests.batch.suites import write_suite
from tests.waiting import until

STAND_IN = f"{sys.executable} {Path(__file__).parent / 'peers' / 'listening_stack.py'}"
BATCH_TIMEOUT_S = 120
pytestmark = pytest.mark.timeout(2 * BATCH_TIMEOUT_S)


def workers_in(folder: Path) -> list[str]:
    """Simulator workers running in `folder` (where their batch started, or a case's)."""
    return [line for line in processes_using(folder) if "egosim.batch.worker" in line]


def one_case_suite(folder: Path, **case: object) -> Path:
    return write_suite(
        folder,
        {
            "stack": {"command": f"{STAND_IN} exit 0 600", "connect_timeout_s": 30},
            # Two seconds of driving at real-time pace: time to look at the processes.
            "clock": {"mode": "sim", "rtf": 1},
            "time_limit_s": 2,
            "criteria": ["no_collision"],
            "cases": [{"name": "only", "scenario": "scenario.yaml", **case}],
        },
    )


def test_fewer_cases_than_workers_run_on_one_worker_and_leave_none(tmp_path: Path) -> None:
    suite = one_case_suite(tmp_path / "suite")
    here, out = tmp_path / "here", tmp_path / "out"
    here.mkdir()
    batch = subprocess.Popen(
        [sys.executable, "-m", "egosim", "batch", str(suite), "--workers", "2", "--out", str(out)],
        cwd=here,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        until((out / "only" / "stack.log").exists, "the case's stack to start", 60)
        # The case's worker only: the other one started ended before the case began.
        assert len(workers_in(tmp_path)) == 1
        _, stderr = batch.communicate(timeout=BATCH_TIMEOUT_S)
    finally:
        if batch.poll() is None:
            batch.kill()
    assert batch.returncode == 0, stderr
    assert [c["status"] for c in read_results(out)["cases"]] == ["passed"]
    assert processes_using(tmp_path) == []


def test_a_suite_that_does_not_load_ends_the_workers_started_for_it(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    suite = one_case_suite(tmp_path / "suite", sweep={"unused": [1]})
    with pytest.raises(SuiteError) as expected:
        load_suite(suite)
    running_while_loading: list[list[str]] = []
    started = min(2, default_workers())

    def load_suite_watched(path: Path) -> list[CaseSpec]:
        # A worker may be between its launcher's exec and its own (its command line not
        # readable for that instant): looked for again until the deadline.
        running_while_loading.append(
            until(
                lambda: found if len(found := workers_in(tmp_path)) == started else None,
                f"{started} workers running while the suite loads",
                10,
            )
        )
        return load_suite(path)

    monkeypatch.setattr(batch_run, "load_suite", load_suite_watched)
    monkeypatch.chdir(tmp_path)  # where the workers start
    assert main(["batch", str(suite), "--workers", "2"]) == EXIT_BAD_INPUT
    assert capsys.readouterr().err == f"egosim batch: {expected.value}\n"
    assert [len(found) for found in running_while_loading] == [started]
    assert workers_in(tmp_path) == []
