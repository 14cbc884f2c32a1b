"""One suite, locally and on Ray actors, gives the same results.json case by case: stacks in
sync mode (so every drive is the same on every run) that drive, crash at once, crash
while driving, hang, never connect; and a car that cannot stop for a red light, stepped at
the physics step and at coarse sync ticks (up to the 1 s a client may ask for). Ray's
workers start their children with SIGINT blocked: a case still stops its simulator
gracefully there, so a crashed or hung stack's drive is scored as it is locally."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest
import yaml

from egosim.batch.early_workers import default_workers
from tests.batch.processes import processes_using
from tests.batch.results_files import comparable, read_results
from tests.batch.suites import STRAIGHT_SCENARIO

STEPPING = f"{sys.executable} {Path(__file__).parent / 'peers' / 'stepping_stack.py'}"
FRAMES = 50
"""A crashing or hanging stack's drive: 50 ticks of 10 ms."""
COARSE_TICKS_MS = [100, 1000]
WALL_LIMIT_S = 6
BATCH_TIMEOUT_S = 300
pytestmark = pytest.mark.timeout(3 * BATCH_TIMEOUT_S)

# The shipped MGeo map puts the stop line at the end of its lane, where the junction lane
# begins; the light (TL1_W) shows red for its first 30 s.
RED_AHEAD = {
    "map": "mgeo_sample",
    "ego": {"start": {"lane": "R3_E_1", "s": 60.5}, "speed_mps": "$speed_mps"},
}


def case(name: str, command: str, scenario: str = "straight.yaml", **extra: Any) -> dict:
    return {"name": name, "scenario": scenario, "parameters": {"command": command}, **extra}


def write_suite(folder: Path) -> Path:
    folder.mkdir()
    (folder / "straight.yaml").write_text(yaml.safe_dump(STRAIGHT_SCENARIO))
    (folder / "red_ahead.yaml").write_text(yaml.safe_dump(RED_AHEAD))
    suite = {
        "stack": {
            "command": "{command}",
            "env": {"STEPPING_TICK_MS": "{tick_ms}"},
            "connect_timeout_s": 10,
        },
        "parameters": {"tick_ms": 0},  # the physics step, 10 ms
        "clock": "sync",
        "time_limit_s": 3,
        "wall_limit_s": WALL_LIMIT_S,
        "bags": "none",
        "criteria": ["no_collision", "no_red_light"],
        "cases": [
            case("hangs", f"{STEPPING} --frames {FRAMES} hang"),
            case("crashes_at_once", "exit 3"),
            case("never_connects", "sleep 600"),
            case("crashes_while_driving", f"{STEPPING} --frames {FRAMES} exit 4"),
            case("drives", STEPPING),
            # 40 m before the red light's stop line, braking as hard as the car can: from
            # 20 m/s it stops in time, from 30 m/s (more than 11 m/s² needed) it cannot.
            case(
                "red_light",
                f"{STEPPING} --brake",
                "red_ahead.yaml",
                sweep={"speed_mps": [20, 30]},
            ),
            # The same in sync ticks of 100 ms and 1 s: the first tick carries the car
            # 2.7 m and 27 m on, the second over the line.
            case(
                "coarse_red_light",
                f"{STEPPING} --brake",
                "red_ahead.yaml",
                sweep={"speed_mps": [20, 30], "tick_ms": COARSE_TICKS_MS},
            ),
        ],
    }
    path = folder / "suite.yaml"
    path.write_text(yaml.safe_dump(suite, sort_keys=False))
    return path


def run_batch(suite: Path, out: Path, *options: str) -> None:
    batch = subprocess.run(
        [sys.executable, "-m", "egosim", "batch", str(suite), "--out", str(out), *options],
        check=False,
        capture_output=True,
        text=True,
        timeout=BATCH_TIMEOUT_S,
    )
    assert batch.returncode == 1, batch.stderr  # some cases fail, as they should
    assert processes_using(out) == []


@pytest.fixture(scope="module")
def suite(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return write_suite(tmp_path_factory.mktemp("suite") / "suite")


@pytest.fixture(scope="module")
def local_out(suite: Path, tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("local")
    run_batch(suite, out, "--workers", "2")
    return out


@pytest.fixture(scope="module")
def on_ray_out(suite: Path, tmp_path_factory: pytest.TempPathFactory) -> Path:
    pytest.importorskip("ray", reason="Ray is an optional extra: pip install egosim[ray]")
    out = tmp_path_factory.mktemp("ray")
    run_batch(suite, out, "--ray")
    return out


@pytest.fixture(scope="module")
def local(local_out: Path) -> dict[str, Any]:
    return read_results(local_out)


@pytest.fixture(scope="module")
def on_ray(on_ray_out: Path) -> dict[str, Any]:
    return read_results(on_ray_out)


def by_name(document: dict[str, Any]) -> dict[str, dict[str, Any]]:
    return {c["name"]: c for c in document["cases"]}


def test_each_case_ends_as_its_stack_made_it(local) -> None:
    cases = by_name(local)
    outcomes = {name: (c["status"], c["reason"], c["end"]) for name, c in cases.items()}
    assert outcomes == {
        "hangs": ("error", f"case exceeded its wall-clock limit of {WALL_LIMIT_S} s", "stopped"),
        "crashes_at_once": ("error", "stack exited with status 3 before connecting", "stopped"),
        "never_connects": ("error", "stack never connected within 10 s", "stopped"),
        "crashes_while_driving": (
            "error",
            "stack exited with status 4 during the drive",
            "stopped",
        ),
        "drives": ("passed", "", "time_limit"),
        "red_light[speed_mps=20]": ("passed", "", "time_limit"),
        "red_light[speed_mps=30]": (
            "failed",
            "no_red_light (red_light_count = 1)",
            "time_limit",
        ),
        **{
            f"coarse_red_light[speed_mps=20,tick_ms={tick}]": ("passed", "", "time_limit")
            for tick in COARSE_TICKS_MS
        },
        **{
            f"coarse_red_light[speed_mps=30,tick_ms={tick}]": (
                "failed",
                "no_red_light (red_light_count = 1)",
                "time_limit",
            )
            for tick in COARSE_TICKS_MS
        },
    }
    # A stack that crashed or hung leaves its drive up to then scored.
    for name in ("hangs", "crashes_while_driving"):
        assert cases[name]["sim_time_s"] == pytest.approx(FRAMES * 0.01)
        assert cases[name]["metrics"]["driving_score"] == 1.0
    assert cases["drives"]["sim_time_s"] == pytest.approx(3.0)


def test_a_red_light_the_car_cannot_stop_for_is_run(local) -> None:
    cases = by_name(local)
    coarse = [f"coarse_red_light[speed_mps={{}},tick_ms={tick}]" for tick in COARSE_TICKS_MS]
    for name in ["red_light[speed_mps=30]", *(c.format(30) for c in coarse)]:
        (run,) = cases[name]["infractions"]
        assert run["kind"] == "red_light", name
        assert (run["x"], run["y"]) == pytest.approx((-19.5, -1.75))  # R3_E_1's end
        # Full braking (about 9 m/s²) from 30 m/s covers the 40 m in a little under 2 s.
        assert 1.5 < run["time_s"] < 2.0, name
    stops = ["red_light[speed_mps=20]", *(c.format(20) for c in coarse)]
    for name in stops:
        assert cases[name]["infractions"] == [], name
        assert cases[name]["metrics"]["distance_m"] < 40.0, name
    # However coarse the tick, the braking is the same drive: it stops at the same place.
    distances = [cases[name]["metrics"]["distance_m"] for name in stops]
    assert distances == pytest.approx([distances[0]] * len(stops), abs=0.01)


@pytest.mark.parametrize("runner", ["local", "on_ray"])
def test_each_worker_keeps_one_simulator_for_its_cases(
    runner: str, request: pytest.FixtureRequest
) -> None:
    out = request.getfixturevalue(f"{runner}_out")
    cases = read_results(out)["cases"]
    # The first line of a case's simulator log: "egosim batch worker PID: case N ...".
    workers = {(out / c["folder"] / "simulator.log").read_text().split()[3] for c in cases}
    slots = 2 if runner == "local" else default_workers()  # Ray: an actor per CPU
    assert len(workers) <= min(slots, len(cases))


def test_ray_tasks_give_the_same_results_case_by_case(local, on_ray) -> None:
    assert on_ray["execution"]["runner"] == "ray"
    ray_cases = by_name(comparable(on_ray))
    for name, result in by_name(comparable(local)).items():
        assert ray_cases[name] == result, name
    assert comparable(on_ray) == comparable(local)
