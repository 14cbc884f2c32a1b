"""A stack that crashes, hangs or never connects makes a failed case with its reason,
never a stuck batch; every case has its own master; nothing is left running."""

from __future__ import annotations

import json
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from egosim.batch.pool import run_local
from egosim.batch.suite import load_suite
from egosim.cli import main
from tests.batch.processes import processes_using
from tests.batch.suites import write_suite

PEER = Path(__file__).parent / "peers" / "listening_stack.py"
STAND_IN = f"{sys.executable} {PEER}"


def case(name: str, command: str, **extra: object) -> dict:
    return {
        "name": name,
        "scenario": "scenario.yaml",
        "parameters": {"command": command},
        **extra,
    }


def robustness_suite(tmp_path: Path, cases: list[dict], **extra: object) -> Path:
    suite = {
        "stack": {"command": "{command}", "connect_timeout_s": 15},
        "clock": {"mode": "sim", "rtf": 0},
        "time_limit_s": 2,
        "criteria": ["no_collision"],
        "cases": cases,
        **extra,
    }
    return write_suite(tmp_path / "suite", suite)


def test_failing_stacks_are_failed_cases_with_their_reason(tmp_path: Path) -> None:
    suite = robustness_suite(
        tmp_path,
        [
            case("fine", f"{STAND_IN} exit 0 600"),
            case("crashes_at_once", "exit 3"),
            case("never_connects", "sleep 600"),
            # Stops 1 s (simulated) into a drive of far more, at real-time pace.
            case("crashes_while_driving", f"{STAND_IN} exit 4 1", time_limit_s=3600),
            case("ignores_sigint", f"{STAND_IN} hang"),
        ],
    )
    out = tmp_path / "out"
    results = run_local(load_suite(suite), str(out), 3, lambda result, running: None)

    def outcome(name: str) -> tuple[str, str]:
        return results[name]["status"], results[name]["reason"]

    assert outcome("fine") == ("passed", "")
    assert outcome("crashes_at_once") == ("error", "stack exited with status 3 before connecting")
    assert outcome("never_connects") == ("error", "stack never connected within 15 s")
    assert outcome("crashes_while_driving") == (
        "error",
        "stack exited with status 4 during the drive",
    )
    assert outcome("ignores_sigint") == ("passed", "")

    # The drive up to the crash is scored and recorded all the same.
    crashed = results["crashes_while_driving"]
    assert crashed["end"] == "stopped" and crashed["bag"] is not None
    assert 0.0 < crashed["sim_time_s"] < 3600.0
    assert results["fine"]["end"] == "time_limit"
    assert results["fine"]["sim_time_s"] == pytest.approx(2.0)
    masters = {
        line
        for r in results.values()
        for line in (out / r["folder"] / "simulator.log").read_text().splitlines()
        if line.startswith("egosim-batch: master")
    }
    assert len(masters) == len(results)  # one master per case, each on its own port
    assert processes_using(out) == []


def test_a_case_past_its_wall_clock_limit_is_stopped(tmp_path: Path) -> None:
    suite = robustness_suite(
        tmp_path,
        [case("slow", f"{STAND_IN} exit 0 600")],
        clock={"mode": "sim", "rtf": 1},
        time_limit_s=600,
        wall_limit_s=3,
    )
    out = tmp_path / "out"
    results = run_local(load_suite(suite), str(out), 1, lambda result, running: None)
    (result,) = results.values()
    assert result["status"] == "error"
    assert result["reason"] == "case exceeded its wall-clock limit of 3 s"
    assert result["end"] == "stopped" and result["metrics"] is not None
    assert processes_using(out) == []


def test_ctrl_c_stops_every_case_and_still_writes_the_results(tmp_path: Path) -> None:
    cases = [case(f"long{k}", f"{STAND_IN} exit 0 600") for k in range(3)]
    suite = robustness_suite(tmp_path, cases, clock={"mode": "sim", "rtf": 1}, time_limit_s=600)
    out = tmp_path / "out"
    batch = subprocess.Popen(
        [sys.executable, "-m", "egosim", "batch", str(suite), "--workers", "2", "--out", str(out)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        deadline = time.monotonic() + 60
        while not list(out.glob("*/stack.log")) and time.monotonic() < deadline:
            time.sleep(0.2)  # until a stack has started
        assert list(out.glob("*/stack.log")), "no stack started within 60 s"
        time.sleep(1.0)
        batch.send_signal(signal.SIGINT)
        _, stderr = batch.communicate(timeout=60)
    finally:
        if batch.poll() is None:
            batch.kill()
    assert batch.returncode == 130, stderr
    document = json.loads((out / "results.json").read_text())
    assert document["execution"]["interrupted"] is True
    statuses = sorted(c["status"] for c in document["cases"])
    assert statuses == ["error", "error", "not_run"]
    assert all(c["reason"] == "interrupted" for c in document["cases"] if c["status"] == "error")
    assert (out / "junit.xml").exists() and (out / "report.html").exists()
    assert processes_using(out) == []


def test_filter_then_rerun_failed_runs_only_what_did_not_pass(tmp_path: Path) -> None:
    suite = robustness_suite(
        tmp_path,
        [
            case("ok", f"{STAND_IN} exit 0 600"),
            # No route to complete: the criterion cannot hold.
            case("broken", f"{STAND_IN} exit 0 600", criteria=["route_completion >= 0.5"]),
        ],
        bags="failed",
    )
    out = tmp_path / "out"
    assert main(["batch", str(suite), "--out", str(out), "--filter", "o*"]) == 0
    first = json.loads((out / "results.json").read_text())
    assert [(c["name"], c["status"]) for c in first["cases"]] == [("ok", "passed")]

    assert main(["batch", str(suite), "--out", str(out), "--rerun-failed"]) == 1
    second = json.loads((out / "results.json").read_text())
    assert second["execution"]["cases_run"] == 1  # "broken" only: "ok" had passed
    assert [(c["name"], c["status"]) for c in second["cases"]] == [
        ("ok", "passed"),
        ("broken", "failed"),
    ]
    assert second["cases"][1]["reason"] == (
        "route_completion >= 0.5 (route_completion is not measured)"
    )
    assert second["cases"][0] == first["cases"][0]
    # Only the case that did not pass keeps its bag.
    assert first["cases"][0]["bag"] is None and not (out / "ok" / "drive.bag").exists()
    assert (out / second["cases"][1]["bag"]).exists()
