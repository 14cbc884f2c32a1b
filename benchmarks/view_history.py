"""What keeping the view's plot history costs: PlotHistory.record per tick (every tick
checks, one in ten at 100 Hz takes a sample of every ego, which reads the ego's state
and lane afresh after the step) against one World.step, the town with its default
scenario; medians, since a loaded machine's preemptions land anywhere. Then a full
minute's memory, and the "history" message a late page gets (building it, its size).

Run: .venv/bin/python benchmarks/view_history.py [--ticks 6100] [--egos 1]
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time

from egosim.bridge import simulation_context
from egosim.view.history import HISTORY_S, SPACING_S, PlotHistory
from egosim.view.snapshot import encode
from egosim.world import World
from egosim.world.map import build_builtin_map
from egosim.world.scenario import load_default_scenario
from egosim.world.vehicle import Pose

DT = 0.01


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--ticks", type=int, default=round((HISTORY_S + 1.0) / DT))
    parser.add_argument("--egos", type=int, default=1)
    args = parser.parse_args()
    world = World(build_builtin_map("town"), load_default_scenario())
    pose = world.ego_status(0).pose
    for k in range(1, args.egos):
        world.add_ego(world.egos[0].vehicle.model.name, Pose(x=pose.x + 8.0 * k, y=pose.y))
    context = simulation_context(world)
    history = PlotHistory()
    step_s: list[float] = []
    check_s: list[float] = []
    sample_s: list[float] = []
    every = round(SPACING_S / DT)  # the first tick takes a sample, then every `every`-th
    for tick in range(args.ticks):
        start = time.perf_counter()
        world.step(DT)
        middle = time.perf_counter()
        history.record(context)
        (check_s if tick % every else sample_s).append(time.perf_counter() - middle)
        step_s.append(middle - start)
    step = statistics.median(step_s)
    check, sample = statistics.median(check_s), statistics.median(sample_s)
    per_tick = (check * (every - 1) + sample) / every
    start = time.perf_counter()
    message = history.message()
    text = encode(message)
    encode_s = time.perf_counter() - start
    kept = len(message["egos"][0]["t"])
    print(f"{args.ticks} ticks of {DT} s, {len(world.egos)} egos, {len(world.objects())} objects")
    print(f"| World.step (median) | {step * 1e6:.0f} us |")
    print(f"| record, a tick without a sample (median) | {check * 1e6:.2f} us |")
    print(f"| record, a tick with a sample (median) | {sample * 1e6:.1f} us |")
    share = per_tick / step
    print(f"| record per tick, the two weighted 9:1 | {per_tick * 1e6:.2f} us ({share:.2%}) |")
    print(f"| samples kept per ego | {kept} (of {round(HISTORY_S / SPACING_S) + 1} at most) |")
    print(f"| memory of the kept samples | {kept_bytes(history) / 1024:.0f} KiB |")
    print(f"| history message, built and encoded | {encode_s * 1e3:.1f} ms |")
    print(f"| history message, JSON | {len(text) / 1024:.0f} KiB |")


def kept_bytes(history: PlotHistory) -> int:
    """The rings and their samples, as the interpreter holds them."""
    rings = history._egos.values()  # the benchmark looks inside on purpose
    return sum(
        sys.getsizeof(ring) + sum(sys.getsizeof(s) + sum(map(sys.getsizeof, s)) for s in ring)
        for ring in rings
    )


if __name__ == "__main__":
    main()
