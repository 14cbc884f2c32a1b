"""What the compiled world step costs at start: compiling its kernels on the first start
after an install (an empty numba cache) against loading them from the cache on every
later start, in fresh processes; the numpy path (EGOSIM_COMPILED=0) for comparison.

Each run imports egosim.world, builds the town with its default scenario and a world
where every kernel runs (the busy town of the tests: NPCs, pedestrians, lane changes,
collisions and contacts), then steps it until the ego has collided.

Usage: .venv/bin/python benchmarks/kernel_start.py [--runs 3]
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

CHILD = """
import json, time
began = time.perf_counter()
from egosim.world import World, kernels
from egosim.world.map import build_builtin_map
from egosim.world.scenario import parse_scenario
from tests.compiled_paths import busy_town, drive
imported = time.perf_counter()
town = build_builtin_map("town")
world = World(town, parse_scenario(busy_town(town), "busy town"))
built = time.perf_counter()
first = []
for k in range(300):
    drive(world, k)
    start = time.perf_counter()
    world.step()
    first.append(time.perf_counter() - start)
assert world.ego_collision_log
print(json.dumps({"active": kernels.ACTIVE, "import": imported - began,
    "build": built - imported, "first_step": first[0],
    "steps_over_5ms": sum(t for t in first if t > 0.005), "slowest_later": max(first[1:])}))
"""


def run(environment: dict[str, str]) -> dict[str, float]:
    result = subprocess.run(
        [sys.executable, "-c", CHILD],
        env={**os.environ, **environment},
        capture_output=True,
        text=True,
        check=True,
        cwd=Path(__file__).resolve().parent.parent,
    )
    reported: dict[str, float] = json.loads(result.stdout.splitlines()[-1])
    return reported


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=3)
    args = parser.parse_args()
    cases: dict[str, list[dict[str, float]]] = {"first start": [], "cached": [], "numpy": []}
    for _ in range(args.runs):
        with tempfile.TemporaryDirectory() as cache:
            cases["first start"].append(run({"NUMBA_CACHE_DIR": cache}))
            cases["cached"].append(run({"NUMBA_CACHE_DIR": cache}))
        cases["numpy"].append(run({"EGOSIM_COMPILED": "0"}))
    print(f"medians of {args.runs} runs, s")
    print(f"{'case':12s} {'import':>7s} {'build':>7s} {'1st step':>9s} {'stalls':>7s}")
    for name, runs in cases.items():
        figures = [
            statistics.median(r[key] for r in runs)
            for key in ("import", "build", "first_step", "steps_over_5ms")
        ]
        print(f"{name:12s} " + " ".join(f"{f:7.3f}" for f in figures))


if __name__ == "__main__":
    main()
