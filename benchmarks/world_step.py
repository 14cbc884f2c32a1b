"""Time per World.step on the town map: 1 ego + N NPCs + 200 pedestrians.

Wall time, and the stepping thread's CPU time (which a machine shared with other work
inflates far less). EGOSIM_COMPILED=0 times the numpy path.

Usage: .venv/bin/python benchmarks/world_step.py [--npcs 100 500 1000] [--pedestrians 200]
       [--warmup-s 5] [--steps 500]
"""

from __future__ import annotations

import argparse
import statistics
import time
from typing import Any

from egosim.world import World
from egosim.world.map import LaneMap, build_builtin_map
from egosim.world.scenario import parse_scenario

NPC_SPACING_M = 25.0
PEDESTRIAN_SPACING_M = 20.0


def crowded_town(lane_map: LaneMap, npcs: int, pedestrians: int) -> dict[str, Any]:
    """Scenario data: NPCs NPC_SPACING_M apart along the road lanes (first lane first,
    round after round), pedestrians on every sidewalk and every other crosswalk."""
    roads = [lane for lane in lane_map.lanes.values() if not lane.is_junction]
    slots = [
        {"lane": lane.id, "s": k * NPC_SPACING_M + 10.0}
        for k in range(int(max(lane.length for lane in roads) // NPC_SPACING_M))
        for lane in roads
        if k * NPC_SPACING_M + 10.0 < lane.length - 10.0
    ]
    if npcs > len(slots):
        raise SystemExit(f"the town has room for {len(slots)} NPCs at this spacing")
    walkers: list[dict[str, Any]] = [
        {"crosswalk": crosswalk} for crosswalk in list(lane_map.crosswalks)[::2]
    ]
    sidewalks = list(lane_map.sidewalks)
    k = 0
    while len(walkers) < pedestrians:
        walkers.append(
            {
                "sidewalk": sidewalks[k % len(sidewalks)],
                "start_s": (k // len(sidewalks)) * PEDESTRIAN_SPACING_M,
            }
        )
        k += 1
    return {
        "map": lane_map.name,
        "seed": 1,
        # Midway between two NPC slots: clear of both wherever on its body the ego's
        # reference point is.
        "ego": {"start": {"lane": "R5_E_1", "s": 10.0 + NPC_SPACING_M / 2.0}},
        "npcs": [{"start": slot} for slot in slots[:npcs]],
        "pedestrians": walkers[:pedestrians],
    }


def time_steps(world: World, warmup_s: float, steps: int) -> tuple[list[float], list[float]]:
    """Wall and CPU milliseconds of each of `steps` steps after `warmup_s` of them."""
    for _ in range(round(warmup_s / world.physics_step_s)):
        world.step()
    wall_ms, cpu_ms = [], []
    for _ in range(steps):
        start, start_cpu = time.perf_counter(), time.thread_time()
        world.step()
        wall_ms.append((time.perf_counter() - start) * 1e3)
        cpu_ms.append((time.thread_time() - start_cpu) * 1e3)
    return wall_ms, cpu_ms


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--npcs", type=int, nargs="+", default=[100, 500, 1000])
    parser.add_argument("--pedestrians", type=int, default=200)
    parser.add_argument("--warmup-s", type=float, default=5.0)
    parser.add_argument("--steps", type=int, default=500)
    args = parser.parse_args()

    lane_map = build_builtin_map("town")
    print(
        f"town map, 1 ego, {args.pedestrians} pedestrians, dt 0.01 s, "
        f"{args.steps} steps after {args.warmup_s:g} s of warm-up"
    )
    for count in args.npcs:
        scenario = parse_scenario(crowded_town(lane_map, count, args.pedestrians), "benchmark")
        world = World(lane_map, scenario)
        durations_ms, cpu_ms = time_steps(world, args.warmup_s, args.steps)
        print(
            f"{count:5d} NPCs: median {statistics.median(durations_ms):.2f} ms, "
            f"p95 {sorted(durations_ms)[int(0.95 * len(durations_ms))]:.2f} ms, "
            f"min {min(durations_ms):.2f} ms per step, "
            f"CPU median {statistics.median(cpu_ms):.3f} ms; "
            f"{len(world.vehicle_collisions)} NPC-NPC collisions"
        )


if __name__ == "__main__":
    main()
