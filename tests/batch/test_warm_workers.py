"""A case run by a warm simulator worker after others, one of which changed all it could of
the simulator and crashed and one of which hung, gives what the same case gives run alone
in a new worker: the same results.json entry, the same graph, parameters and ego state
for its stack to find, the same replies to every tick, the same bag."""

from __future__ import annotations

import hashlib
import json
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest
import yaml
from rosbags.rosbag1 import Reader

from egosim.batch.case_runner import run_case
from egosim.batch.suite import load_suite
from egosim.batch.warm_simulator import WarmSimulator
from tests.batch.processes import processes_using
from tests.batch.results_files import comparable, read_results
from tests.batch.suites import STRAIGHT_SCENARIO

PEERS = Path(__file__).parent / "peers"
PROBE = f"{sys.executable} {PEERS / 'probe_stack.py'}"
STEPPING = f"{sys.executable} {PEERS / 'stepping_stack.py'}"
WALL_LIMIT_S = 6
BATCH_TIMEOUT_S = 240
pytestmark = pytest.mark.timeout(3 * BATCH_TIMEOUT_S)


def write_suite(folder: Path) -> Path:
    folder.mkdir()
    (folder / "straight.yaml").write_text(yaml.safe_dump(STRAIGHT_SCENARIO))
    cases = [
        ("meddles", f"{PROBE} meddle"),
        ("hangs", f"{STEPPING} --frames 20 hang"),
        ("observes", f"{PROBE} observe"),
    ]
    suite = {
        "stack": {"command": "{command}", "connect_timeout_s": 30},
        "clock": "sync",
        "time_limit_s": 3,
        "wall_limit_s": WALL_LIMIT_S,
        "criteria": ["no_collision"],
        "cases": [
            {
                "name": name,
                "scenario": "straight.yaml",
                "parameters": {"command": command},
            }
            for name, command in cases
        ],
    }
    path = folder / "suite.yaml"
    path.write_text(yaml.safe_dump(suite, sort_keys=False))
    return path


def run_batch(suite: Path, out: Path, *options: str) -> dict[str, Any]:
    batch = subprocess.run(
        [sys.executable, "-m", "egosim", "batch", str(suite), "--out", str(out), *options],
        check=False,
        capture_output=True,
        text=True,
        timeout=BATCH_TIMEOUT_S,
    )
    assert batch.returncode in (0, 1), batch.stderr
    assert processes_using(out) == []
    return read_results(out)


@pytest.fixture(scope="module")
def suite(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return write_suite(tmp_path_factory.mktemp("suite") / "suite")


@pytest.fixture(scope="module")
def after_others(suite: Path, tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("after_others")
    run_batch(suite, out, "--workers", "1")
    return out


@pytest.fixture(scope="module")
def alone(suite: Path, tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("alone")
    run_batch(suite, out, "--workers", "1", "--filter", "observes")
    return out


def entry(out: Path, name: str) -> dict[str, Any]:
    (case,) = [c for c in comparable(read_results(out))["cases"] if c["name"] == name]
    return case


def observations(out: Path) -> dict[str, Any]:
    return json.loads((out / "observes" / "observed.json").read_text())


def bag_messages(path: Path) -> dict[str, list[tuple[int, str]]]:
    """Each topic's messages as (time, md5 of the bytes)."""
    topics: dict[str, list[tuple[int, str]]] = {}
    with Reader(path) as reader:
        for connection, stamp, raw in reader.messages():
            topics.setdefault(connection.topic, []).append((stamp, hashlib.md5(raw).hexdigest()))
    return topics


def test_the_earlier_cases_crashed_and_hung_in_the_same_worker(after_others: Path) -> None:
    document = read_results(after_others)
    outcomes = {c["name"]: (c["status"], c["reason"]) for c in document["cases"]}
    assert outcomes == {
        "meddles": ("error", "stack exited with status 3 during the drive"),
        "hangs": ("error", f"case exceeded its wall-clock limit of {WALL_LIMIT_S} s"),
        "observes": ("passed", ""),
    }
    # One warm worker ran them all (the hung case's between the other two).
    pids = {(after_others / name / "simulator.pid").read_text() for name in ("meddles", "observes")}
    assert len(pids) == 1


def test_a_case_after_others_gives_the_entry_it_gives_alone(after_others, alone) -> None:
    assert entry(after_others, "observes") == entry(alone, "observes")
    assert [c["name"] for c in read_results(alone)["cases"]] == ["observes"]


def test_its_stack_finds_what_it_finds_alone(after_others, alone) -> None:
    observed, fresh = (observations(out) for out in (after_others, alone))
    assert observed == fresh
    assert observed["params"] == ["/run_id", "/use_sim_time"]  # none the meddler set
    assert observed["ego"]["ctrl_mode"] == 3  # external: the meddling stack's autopilot is gone
    assert observed["sync_start"]["time_step"] == 10  # the physics step, not the 20 ms tick


def test_its_bag_is_the_bag_it_records_alone(after_others, alone) -> None:
    recorded = bag_messages(after_others / "observes" / "drive.bag")
    assert recorded == bag_messages(alone / "observes" / "drive.bag")
    assert len(recorded["/Ego_topic"]) in (20, 21)  # 50 Hz over 40 ticks of 10 ms


@pytest.mark.parametrize("started", ["with its case", "ahead of its case"])
def test_a_worker_that_cannot_start_says_why_in_the_case_log(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, started: str
) -> None:
    broken = tmp_path / "broken" / "egosim"
    broken.mkdir(parents=True)
    (broken / "__init__.py").write_text("raise ImportError('this egosim is broken')\n")
    monkeypatch.setenv("PYTHONPATH", str(broken.parent))
    (case,) = load_suite(write_suite(tmp_path / "suite"))[-1:]
    simulator = WarmSimulator()
    if started == "ahead of its case":  # as the batch command starts it
        simulator.start()
    try:
        result = run_case(case, str(tmp_path / "out"), simulator)
    finally:
        simulator.close()
    assert result["status"] == "error"
    assert result["reason"] == "simulator did not start"
    assert result["log_tail"]["file"] == "simulator.log"
    assert "ImportError: this egosim is broken" in "\n".join(result["log_tail"]["lines"])
