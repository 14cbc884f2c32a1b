"""Cost of scoring: one DriveEvaluator.observe against one World.step, town map with its
default scenario (NPCs, pedestrians, lights), 100 Hz physics; and of `egosim run`'s drive
log stage (the same rules on every ego, logging what they find), run alone on a second
world of the same scenario.

Usage: .venv/bin/python benchmarks/evaluation_step.py [--steps 2000]
"""

from __future__ import annotations

import argparse
import statistics
import time

from egosim.app.drive_log import DriveLog
from egosim.bridge import simulation_context
from egosim.bridge.pipeline import Tick
from egosim.evaluation import DriveEvaluator, Route
from egosim.world import World
from egosim.world.map import build_builtin_map
from egosim.world.scenario import load_default_scenario


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=2000)
    args = parser.parse_args()
    town = build_builtin_map("town")
    world = World(town, load_default_scenario())
    lane = town.lanes[town.lane_ids[0]]
    evaluator = DriveEvaluator(world, Route(lane.centerline[:, :2]))
    step_s = observe_s = 0.0
    for _ in range(args.steps):
        start = time.perf_counter()
        world.step()
        middle = time.perf_counter()
        evaluator.observe(world)
        end = time.perf_counter()
        step_s += middle - start
        observe_s += end - middle
    logged = World(town, load_default_scenario())
    context, drive_log, log_s = simulation_context(logged), DriveLog(), []
    for _ in range(args.steps):
        logged.step()
        start = time.perf_counter()
        drive_log.run(context, Tick(logged.physics_step_s, logged.sim_time))
        log_s.append(time.perf_counter() - start)
    print(f"{len(world.objects())} objects, {args.steps} steps")
    print(f"| World.step | {step_s / args.steps * 1e6:.0f} µs |")
    print(f"| DriveEvaluator.observe | {observe_s / args.steps * 1e6:.0f} µs |")
    mean, median = statistics.fmean(log_s), statistics.median(log_s)
    print(f"| DriveLog.run (drive log stage), mean | {mean * 1e6:.0f} µs |")
    print(f"| DriveLog.run (drive log stage), median | {median * 1e6:.0f} µs |")


if __name__ == "__main__":
    main()
