"""Instructions per World.step, counted by valgrind's callgrind: a measure that the load
of a shared machine does not change, for comparing two versions of the world.

Each world is stepped under `valgrind --tool=callgrind` twice, 0 and then --steps steps
after the same warm-up; the difference of the two counts over --steps is one step's
cost. The hash seed and OpenBLAS's threads are fixed so that counts repeat (an idle
OpenBLAS thread otherwise adds a count that varies from run to run). Worlds:

  town     the town with its default scenario (8 NPCs, 6 pedestrians, 4 obstacles)
  crowded  the town with 100 NPCs and 200 pedestrians (benchmarks/world_step.py)
  replay      the town's default scenario while a replay shows the ego and the
              pedestrians (the NPCs simulated among them), a new recorded frame per step
  storyboard  benchmarks/storyboard_step.py's 20-entity storyboard on the highway, the
              scenario driving the ego; each step is the storyboard's, then World.step
  morai       a MORAI scenario file on the town (benchmarks/morai_scenario.py): 50 NPCs,
              50 pedestrians, 50 cones, the NPCs and pedestrians waiting for the ego to
              come within 30 m (most stay dormant: the wake check runs every step)

Usage: .venv/bin/python benchmarks/world_step_instructions.py
       [--worlds town crowded replay storyboard morai] [--steps 300] [--warmup 200]
"""

from __future__ import annotations

import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
from morai_scenario import document
from storyboard_step import ROOT, benchmark_text
from world_step import crowded_town

from egosim.maps import load_map
from egosim.scenario_files import openscenario_scenario
from egosim.world import World
from egosim.world.map import build_builtin_map
from egosim.world.openscenario import read_openscenario
from egosim.world.recorded_scene import RecordedEgo, RecordedScene
from egosim.world.scenario import ScenarioLoadOptions, load_default_scenario, parse_scenario
from egosim.world.scenario.morai import read_morai_scenario
from egosim.world.traffic import ObjectTable, ObjectType
from egosim.world.vehicle import Pose

WORLDS = ("town", "crowded", "replay", "storyboard", "morai")
DT = 0.01
REPLAYED_PEDESTRIANS = 6
MORAI_ENTRIES = 50
MORAI_ACTIVE_DISTANCE_M = 30.0


def world_of(name: str) -> World:
    if name == "storyboard":
        world = World(load_map(str(ROOT / "examples" / "openscenario" / "highway.xodr")))
        program = read_openscenario(benchmark_text(), "benchmark.xosc")
        world.load_scenario(
            openscenario_scenario(program), ScenarioLoadOptions(scenario_drives_ego=True)
        )
        return world
    town = build_builtin_map("town")
    if name == "crowded":
        return World(town, parse_scenario(crowded_town(town, 100, 200), "benchmark"))
    if name == "morai":
        text = json.dumps(document(town, MORAI_ENTRIES, MORAI_ACTIVE_DISTANCE_M))
        return World(town, read_morai_scenario(text, "benchmark.json").scenario)
    return World(town, load_default_scenario())


def replay_frame(k: int) -> RecordedScene:
    """Step k's recorded frame: the ego driving east on its lane at 5 m/s, pedestrians
    walking along the lane beside it at 0.5 m/s."""
    t = k * DT
    n = REPLAYED_PEDESTRIANS
    walkers = ObjectTable(
        unique_ids=np.arange(500, 500 + n, dtype=np.int64),
        object_types=np.full(n, int(ObjectType.PEDESTRIAN), np.int64),
        names=("Man",) * n,
        positions=np.column_stack(
            (np.linspace(-40.0, 40.0, n) + 0.5 * t, np.full(n, -95.25), np.zeros(n))
        ),
        headings=np.zeros(n),
        velocities=np.tile((0.5, 0.0, 0.0), (n, 1)),
        accelerations=np.zeros((n, 3)),
        sizes=np.tile((0.6, 0.6, 1.8), (n, 1)),
    )
    ego = RecordedEgo(Pose(x=-46.0 + 5.0 * (t % 10.0), y=-91.75), 5.0, 0.0, 0.0)
    return RecordedScene(ego=ego, pedestrians=walkers)


def step(name: str, warmup: int, steps: int) -> None:
    """What runs under callgrind."""
    world = world_of(name)
    storyboard = world.storyboard
    for k in range(warmup + steps):
        if name == "replay":
            world.show_recorded(replay_frame(k))
        if storyboard is not None:
            storyboard.step(DT, True)
        world.step(DT)


def instructions(name: str, warmup: int, steps: int, folder: Path) -> int:
    """Instructions callgrind counts for building world `name` and stepping it."""
    env = dict(os.environ, PYTHONHASHSEED="0", OPENBLAS_NUM_THREADS="1")
    result = subprocess.run(
        [
            "valgrind",
            "--tool=callgrind",
            f"--callgrind-out-file={folder / f'{name}-{steps}.out'}",
            sys.executable,
            __file__,
            "--child",
            name,
            str(warmup),
            str(steps),
        ],
        env=env,
        capture_output=True,
        text=True,
        check=True,
    )
    collected = re.search(r"Collected : (\d+)", result.stderr)
    if collected is None:
        raise SystemExit(f"no count in callgrind's output:\n{result.stderr}")
    return int(collected.group(1))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--worlds", nargs="+", choices=WORLDS, default=list(WORLDS))
    parser.add_argument("--steps", type=int, default=300)
    parser.add_argument("--warmup", type=int, default=200)
    parser.add_argument("--child", nargs=3, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child:
        name, warmup, steps = args.child
        step(name, int(warmup), int(steps))
        return
    if shutil.which("valgrind") is None:
        print("skipped: valgrind is not installed (apt-get install valgrind)")
        return
    print(f"callgrind, dt {DT} s, {args.steps} steps after {args.warmup} of warm-up")
    with tempfile.TemporaryDirectory() as folder:
        for name in args.worlds:
            base = instructions(name, args.warmup, 0, Path(folder))
            stepped = instructions(name, args.warmup, args.steps, Path(folder))
            print(f"{name:8s} {(stepped - base) / args.steps:12,.0f} instructions per step")


if __name__ == "__main__":
    main()
