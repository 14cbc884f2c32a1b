"""Where a sync-mode tick's time goes, in-process and without ROS: `World.step` on the
town with its default scenario, then building and serialising every published row of
the default network settings that is due at its rate (as the bridge does after each
step); no sockets, so sending is not included (benchmarks/sync_mode.py measures it).
A second run times the parts of `World.step` (each wrapped in a timer, about 0.2 us
each of overhead) on a fresh world.

Usage: .venv/bin/python benchmarks/sync_tick_parts.py [--ticks 2000] [--warmup 200]
"""

from __future__ import annotations

import argparse
import time
from collections.abc import Callable
from pathlib import Path

from egosim.app.clock import HeaderClock
from egosim.app.options import ClockMode, RunOptions
from egosim.app.runner import build_world
from egosim.bridge.bindings import HANDLERS
from egosim.bridge.context import BridgeContext
from egosim.bridge.network import default_network_settings
from egosim.bridge.releases import CANONICAL_PROFILE, canonical
from egosim.bridge.sensor_rig import SensorRig
from egosim.bridge.sync_mode import SyncSession
from egosim.bridge.table import Direction
from egosim.msgs import get_profile
from egosim.world import World

TICK_S = 0.01


def world_parts(world: World) -> dict[str, tuple[object, str]]:
    """The calls `World.step` makes, by what they do: (owner, attribute name)."""
    return {
        "signal programs": (world.signals, "step"),
        "road surface under the ego": (world, "_road_surfaces"),
        "ego dynamics": (world.egos[0].vehicle, "step"),
        "lane projection (egos, walkers)": (world, "_lane_users"),
        "NPC step": (world.npcs, "step"),
        "pedestrian step": (world.pedestrians, "step"),
        "collision check": (world, "_collide"),
    }


def time_world_parts(ticks: int, warmup: int) -> None:
    world = build_world(RunOptions(clock=ClockMode.SYNC))
    parts = world_parts(world)
    spent = dict.fromkeys(parts, 0.0)
    for label, (owner, name) in parts.items():
        setattr(owner, name, timed(getattr(owner, name), label, spent))
    for _ in range(warmup):
        world.step(TICK_S)
    spent.update(dict.fromkeys(spent, 0.0))
    began = time.perf_counter()
    for _ in range(ticks):
        world.step(TICK_S)
    whole = time.perf_counter() - began
    print(f"{'World.step, parts timed':44s} {whole / ticks * 1e6:8.0f} us per tick")
    for label, seconds in spent.items():
        print(f"  {label:42s} {seconds / ticks * 1e6:8.0f} us per tick")
    rest = whole - sum(spent.values())
    print(
        f"  {'the rest (lights view, occupants, glue)':42s} {rest / ticks * 1e6:8.0f} us per tick"
    )


def timed(
    call: Callable[..., object], label: str, spent: dict[str, float]
) -> Callable[..., object]:
    def run(*args: object, **kwargs: object) -> object:
        began = time.perf_counter()
        try:
            return call(*args, **kwargs)
        finally:
            spent[label] += time.perf_counter() - began

    return run


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--ticks", type=int, default=2000)
    parser.add_argument("--warmup", type=int, default=200)
    args = parser.parse_args()

    world = build_world(RunOptions(clock=ClockMode.SYNC))
    settings = default_network_settings()
    context = BridgeContext(
        get_profile(CANONICAL_PROFILE),
        world,
        HeaderClock(ClockMode.SYNC, world),
        data_roots=(Path.cwd(),),
        sensors=SensorRig(settings.sensors, world.map.georef),
        sync=SyncSession(),
        publishes_clock=True,
    )
    rows = [row for row in settings.enabled_rows() if row.direction is Direction.PUBLISH]
    periods = [1.0 / row.rate_hz if row.rate_hz else None for row in rows]
    next_due = [0.0] * len(rows)
    spent = [0.0] * len(rows)
    built = [0] * len(rows)
    world_s = 0.0
    for tick in range(args.warmup + args.ticks):
        measured = tick >= args.warmup
        began = time.perf_counter()
        world.step(TICK_S)
        stepped = time.perf_counter()
        if measured:
            world_s += stepped - began
        now = (tick + 1) * TICK_S
        for k, row in enumerate(rows):
            period = periods[k]
            if period is not None and now + 1e-9 < next_due[k]:
                continue
            if period is not None:
                next_due[k] = max(next_due[k] + period, now)
            start = time.perf_counter()
            messages = HANDLERS.publishers[row.key](context)
            if messages is None:
                continue
            message_type = canonical(row.type_name)
            for message in messages if isinstance(messages, list | tuple) else (messages,):
                message_type.serialize(message)
            if measured:
                spent[k] += time.perf_counter() - start
                built[k] += 1

    print(f"town + default scenario, {args.ticks} ticks of {TICK_S * 1000:.0f} ms")
    print(f"{'World.step':44s} {world_s / args.ticks * 1e6:8.0f} us per tick")
    total = 0.0
    for k, row in enumerate(rows):
        if built[k]:
            per_tick = spent[k] / args.ticks * 1e6
            total += per_tick
            print(
                f"{row.name:44s} {spent[k] / built[k] * 1e6:8.0f} us per publish "
                f"{per_tick:8.1f} us per tick"
            )
    print(f"{'building + serialising, all rows':44s} {total:8.0f} us per tick")
    time_world_parts(args.ticks, args.warmup)


if __name__ == "__main__":
    main()
