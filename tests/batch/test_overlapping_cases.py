"""A slot's cases overlap at their ends (the next stack starts while the last case drives,
the last stack ends while the next case runs), and still no two cases share a master, a
graph or a bag: each stack meets only its own case's master, from its start to its end,
and each bag holds its own drive."""

from __future__ import annotations

import itertools
import json
import sys
from pathlib import Path
from typing import Any

import pytest
from rosbags.rosbag1 import Reader

from egosim.batch.local_slot import AHEAD_LIMIT_S
from egosim.batch.pool import run_local
from egosim.batch.suite import load_suite
from tests.batch.processes import processes_using
from tests.batch.suites import write_suite

PEERS = Path(__file__).parent / "peers"
STACK = f"{sys.executable} {PEERS / 'lingering_stack.py'}"
HANGING = f"{sys.executable} {PEERS / 'stepping_stack.py'} --frames 20 hang"
TICKS = (150, 160, 170, 180)
"""Each case's drive, in physics steps of 10 ms (its time limit): over a second of wall
time each, longer than a stack takes to start."""
SIMULATOR_NODE = "/egosim"
WALL_LIMIT_S = 8
pytestmark = pytest.mark.timeout(300)


@pytest.fixture(scope="module")
def cases(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, dict[str, Any]]:
    folder = tmp_path_factory.mktemp("overlap")
    suite = write_suite(
        folder / "suite",
        {
            "stack": {"command": STACK, "connect_timeout_s": 60},
            "clock": "sync",
            "criteria": ["no_collision"],
            "cases": [
                {"name": f"ticks_{ticks}", "scenario": "scenario.yaml", "time_limit_s": ticks / 100}
                for ticks in TICKS
            ],
        },
    )
    out = folder / "out"
    results = run_local(load_suite(suite), str(out), 1, lambda result, running: None)
    assert processes_using(out) == []
    return out, results


def met(out: Path, ticks: int) -> dict[str, Any]:
    return json.loads((out / f"ticks_{ticks}" / "met.json").read_text())


def test_the_cases_overlapped_at_both_ends(cases) -> None:
    out, results = cases
    assert {r["status"] for r in results.values()} == {"passed"}
    stacks = [met(out, ticks) for ticks in TICKS]
    pairs = list(itertools.pairwise(stacks))
    # A stack began before the case before it had ended its drive (started ahead of its
    # simulator, it found no simulator in its graph), and one ended after the next began.
    ahead = [later for earlier, later in pairs if later["began"] < earlier["drive_over"]]
    assert ahead and all(SIMULATOR_NODE not in stack["first_nodes"] for stack in ahead)
    assert any(earlier["ended"] > later["began"] for earlier, later in pairs)


def test_each_stack_met_only_its_own_master_and_graph(cases) -> None:
    out, _ = cases
    stacks = [met(out, ticks) for ticks in TICKS]
    for stack in stacks:
        (run_id,) = stack["run_ids"]  # the same master throughout, always answering
        assert run_id != "unanswered"
        assert set(stack["nodes"]) <= {SIMULATOR_NODE}
    assert len({stack["run_ids"][0] for stack in stacks}) == len(TICKS)


def test_each_bag_holds_its_own_drive(cases) -> None:
    out, results = cases
    for ticks in TICKS:
        with Reader(out / f"ticks_{ticks}" / "drive.bag") as reader:
            clock = [c for c in reader.connections if c.topic == "/clock"]
            stamps = [stamp for _, stamp, _ in reader.messages(connections=clock)]
        assert len(stamps) in (ticks, ticks + 1)  # one /clock per step of its own drive
        assert results[f"ticks_{ticks}"]["sim_time_s"] == pytest.approx(ticks / 100)


def test_a_stack_started_ahead_of_a_busy_simulator_is_started_afresh(tmp_path: Path) -> None:
    # The second case hangs until its wall-clock limit, well past the drives seen so far
    # and past AHEAD_LIMIT_S: the third case's stack, started ahead, is stopped, and the
    # case starts afresh (in a folder of its own again) once the simulator is free.
    assert AHEAD_LIMIT_S < WALL_LIMIT_S
    suite = write_suite(
        tmp_path / "suite",
        {
            "stack": {"command": "{command}", "connect_timeout_s": 60},
            "clock": "sync",
            "time_limit_s": 1.5,
            "wall_limit_s": WALL_LIMIT_S,
            "criteria": ["no_collision"],
            "cases": [
                {"name": name, "scenario": "scenario.yaml", "parameters": {"command": command}}
                for name, command in (("first", STACK), ("hangs", HANGING), ("after", STACK))
            ],
        },
    )
    out = tmp_path / "out"
    results = run_local(load_suite(suite), str(out), 1, lambda result, running: None)
    assert processes_using(out) == []
    assert results["hangs"]["reason"] == f"case exceeded its wall-clock limit of {WALL_LIMIT_S} s"
    assert results["after"]["status"] == "passed"
    assert len((out / "after" / "starts").read_text().splitlines()) == 1
    stack = json.loads((out / "after" / "met.json").read_text())
    assert len(stack["run_ids"]) == 1 and stack["run_ids"] != ["unanswered"]
