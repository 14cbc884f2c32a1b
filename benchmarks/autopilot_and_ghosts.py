"""Cost of ctrl_mode auto and of NPC ghosts on the town map with its default traffic.

- autopilot: drive_autopilots (one ego in auto mode: object table, lane placement of
  every road user, the autopilot's command) per step, next to World.step itself;
- NPC ghosts: World.place_npc_ghosts for one NpcGhostCmd of N ghosts, and World.step
  with N ghosts standing in the town.

Usage: .venv/bin/python benchmarks/autopilot_and_ghosts.py [--steps 500] [--ghosts 10 100 500]
"""

from __future__ import annotations

import argparse
import functools
import statistics
import time
from collections.abc import Callable

from egosim.bridge import ControlMode, simulation_context
from egosim.bridge.control_modes import drive_autopilots
from egosim.world import World
from egosim.world.map import build_builtin_map
from egosim.world.scenario import load_default_scenario
from egosim.world.traffic.ghosts import GhostPlacement
from egosim.world.vehicle import DEFAULT_EGO_MODEL, vehicle_model

WARMUP_STEPS = 200


def _ms(action: Callable[[], object], repeats: int) -> list[float]:
    durations = []
    for _ in range(repeats):
        start = time.perf_counter()
        action()
        durations.append((time.perf_counter() - start) * 1e3)
    return durations


def _report(label: str, durations_ms: list[float]) -> None:
    p95 = sorted(durations_ms)[int(0.95 * len(durations_ms))]
    print(f"{label}: median {statistics.median(durations_ms):.3f} ms, p95 {p95:.3f} ms")


def _ghosts(world: World, count: int, shift_m: float) -> list[GhostPlacement]:
    """`count` ghosts spread over the road lanes, `shift_m` along them."""
    lane_map = world.map
    roads = [lane for lane in lane_map.lanes.values() if not lane.is_junction]
    model = vehicle_model(DEFAULT_EGO_MODEL)
    placements = []
    for k in range(count):
        lane = roads[k % len(roads)]
        s = (10.0 + 12.0 * (k // len(roads)) + shift_m) % lane.length
        x, y, z, heading = lane_map.pose_at(lane.id, s)
        placements.append(GhostPlacement(100_000 + k, model, (x, y, z), heading, 10.0))
    return placements


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=500)
    parser.add_argument("--ghosts", type=int, nargs="+", default=[10, 100, 500])
    args = parser.parse_args()
    lane_map = build_builtin_map("town")

    world = World(lane_map, load_default_scenario())
    context = simulation_context(world)
    context.ego_session(world.egos[0]).set_ctrl_mode(ControlMode.AUTO, by="the benchmark")
    for _ in range(WARMUP_STEPS):
        drive_autopilots(context)
        world.step()
    print(f"town, default scenario: {len(world.npcs)} NPCs, {len(world.pedestrians)} pedestrians")
    autopilot, step = [], []
    for _ in range(args.steps):
        autopilot += _ms(lambda: drive_autopilots(context), 1)
        step += _ms(world.step, 1)
    _report("drive_autopilots (1 ego in auto)", autopilot)
    _report("World.step", step)

    for count in args.ghosts:
        world = World(lane_map, load_default_scenario())
        world.place_npc_ghosts(_ghosts(world, count, 0.0))
        moves = [_ghosts(world, count, 0.1 * k) for k in range(1, 51)]
        place = world.place_npc_ghosts
        placing = [_ms(functools.partial(place, m), 1)[0] for m in moves]
        _report(f"place_npc_ghosts, {count} ghosts", placing)
        _report(f"World.step with {count} ghosts", _ms(world.step, args.steps))


if __name__ == "__main__":
    main()
