"""Cost of one sync-mode request for a later frame while many others wait for theirs.

In-process, no ROS: a `--clock sync` bridge context on the straight map, `--waiting`
requests queued for later frames, then `--requests` more timed one by one.

Usage: .venv/bin/python benchmarks/sync_requests.py [--waiting 9000] [--requests 900]
"""

from __future__ import annotations

import argparse
import time

from egosim.bridge import simulation_context
from egosim.bridge.context import BridgeContext
from egosim.bridge.sync.sync_mode import at_frame
from egosim.world import World
from egosim.world.map import build_builtin_map


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--waiting", type=int, default=9000)
    parser.add_argument("--requests", type=int, default=900)
    args = parser.parse_args()

    world = World(build_builtin_map("straight"))
    context = simulation_context(world)
    context.sync.start("benchmark", time_step_ms=10)
    row = context.row("sync_mode_ctrl_cmd")

    def nothing(_: BridgeContext) -> bool:
        return True

    for k in range(args.waiting):
        at_frame(context, row, 2 + k, nothing)
    began = time.perf_counter()
    for k in range(args.requests):
        at_frame(context, row, 2 + args.waiting + k, nothing)
    per_request = (time.perf_counter() - began) / args.requests
    print(f"{per_request * 1e6:.2f} us per request with {args.waiting} or more waiting")


if __name__ == "__main__":
    main()
