"""What the compiled world step costs at start: compiling its kernels on the first start
after an install (an empty numba cache) against loading them from the cache on every
later start, in fresh processes; the numpy path (EGOSIM_COMPILED=0) for comparison.

Each run imports egosim.world, builds a world where every kernel runs (the busy town
of the tests: NPCs, pedestrians, lane changes, collisions and contacts) and steps it
300 times (the ego collides, so the contact kernels run too): the time to import, to
build, of the first step (most kernels compile or load there), of the slowest later
step (the first collision's kernels) and of all 300 steps.

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
    "build": built - imported, "first_step": first[0], "steps": sum(first),
    "slowest_later": max(first[1:])}))
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
    keys = ("import", "build", "first_step", "slowest_later", "steps")
    heads = ("import", "build", "1st step", "slowest", "300 steps")
    print(f"{'case':12s} " + " ".join(f"{head:>9s}" for head in heads))
    for name, runs in cases.items():
        figures = [statistics.median(r[key] for r in runs) for key in keys]
        print(f"{name:12s} " + " ".join(f"{f:9.3f}" for f in figures))


if __name__ == "__main__":
    main()
