"""Where a sync-mode tick's time goes, in-process and without ROS: `World.step` on the
town with its default scenario, then building and serialising every published row of
the default network settings that is due at its rate (as the bridge does after each
step); no sockets, so sending is not included (benchmarks/sync_mode.py measures it).

Usage: .venv/bin/python benchmarks/sync_tick_parts.py [--ticks 2000] [--warmup 200]
"""

from __future__ import annotations

import argparse
import time
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

TICK_S = 0.01


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


if __name__ == "__main__":
    main()
