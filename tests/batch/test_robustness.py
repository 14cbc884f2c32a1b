"""A stack that crashes, hangs or never connects makes a failed case with its reason,
never a stuck batch; every case has its own master; nothing is left running."""

from __future__ import annotations

import html
import json
import signal
import subprocess
import sys
import time
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from egosim.batch.pool import run_local
from egosim.batch.suite import load_suite
from egosim.cli import main
from tests.batch.processes import processes_using
from tests.batch.suites import write_suite
from tests.debian_ros import ROS_PYTHON, require_ros

PEERS = Path(__file__).parent / "peers"
STAND_IN = f"{sys.executable} {PEERS / 'listening_stack.py'}"
MORAI_NODE = f"{ROS_PYTHON} {PEERS / 'morai_node.py'}"
MISSING_MODULE = "ModuleNotFoundError: No module named 'morai_msgs'"


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

    def tail(name: str) -> dict | None:
        return results[name]["log_tail"]

    assert outcome("fine") == ("passed", "")
    assert outcome("crashes_at_once") == ("error", "stack exited with status 3 before connecting")
    assert outcome("never_connects") == ("error", "stack never connected within 15 s")
    assert outcome("crashes_while_driving") == (
        "error",
        "stack exited with status 4 during the drive",
    )
    assert outcome("ignores_sigint") == ("passed", "")
    # Beside each verdict, the end of the log that explains it (empty: nothing written).
    assert tail("crashes_at_once") == {"file": "stack.log", "lines": []}
    assert tail("never_connects") == {"file": "stack.log", "lines": []}
    assert tail("crashes_while_driving")["file"] == "stack.log"
    assert tail("fine") is None and tail("ignores_sigint") is None

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


def test_a_stack_that_cannot_import_its_messages_shows_its_traceback(tmp_path: Path) -> None:
    require_ros()
    # PYTHONPATH empty: no exported morai_msgs reach the node, whatever the caller has.
    suite = robustness_suite(
        tmp_path,
        [case("no_messages", MORAI_NODE)],
        stack={"command": "{command}", "env": {"PYTHONPATH": ""}},
    )
    out = tmp_path / "out"
    batch = subprocess.run(
        [sys.executable, "-m", "egosim", "batch", str(suite), "--out", str(out)],
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )
    assert batch.returncode == 1, batch.stderr
    # results.json: the reason as before, the log's last lines beside it.
    (result,) = json.loads((out / "results.json").read_text())["cases"]
    assert result["reason"] == "stack exited with status 1 before connecting"
    tail = result["log_tail"]
    assert tail["file"] == "stack.log"
    assert tail["lines"][0] == "Traceback (most recent call last):"
    assert any("from morai_msgs.msg import CtrlCmd" in line for line in tail["lines"])
    assert tail["lines"][-1] == MISSING_MODULE
    # The console: the verdict, then those lines under it.
    console = batch.stderr.splitlines()
    verdict = next(k for k, line in enumerate(console) if line.startswith("ERROR"))
    assert console[verdict].split() == ["ERROR", "no_messages", *result["reason"].split()]
    shown = console[verdict + 1 : verdict + 2 + len(tail["lines"])]
    assert shown == [
        " " * 8 + "stack.log, last lines:",
        *(" " * 10 + line for line in tail["lines"]),
    ]
    # JUnit: the error's text carries the traceback; the HTML report shows it too.
    error = ET.parse(out / "junit.xml").find("testcase/error")
    assert error is not None and error.get("message") == result["reason"]
    assert error.text is not None and MISSING_MODULE in error.text
    assert "Traceback (most recent call last):" in error.text
    report = (out / "report.html").read_text()
    assert html.escape(MISSING_MODULE) in report
    assert processes_using(out) == []
