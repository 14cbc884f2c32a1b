"""What each sensor row costs to build and serialise, per publish, inside a running tick:
the town with its default scenario, the ego parked (as the sync benchmarks leave it) or
driving a weaving line, every row built once after every tick of 10 ms (CPU time of
the build and the serialisation, so other processes' load counts less). The world's
readings the rows share (the ego's status, the object table) are read first, timed on
their own, as the publish stage shares them between its rows. Also prints a
digest of every message's bytes per row: the same world gives the same digests before
and after a change to the builders.

With --first-start, instead: what the LiDAR's and the radar's first readings cost in a
fresh process, with an empty numba cache (the first start after an install compiles
their kernels) and then with the cache that start filled.

Usage: .venv/bin/python benchmarks/sensor_rows.py [--ticks 1000] [--warmup 200]
       [--first-start]
"""

from __future__ import annotations

import argparse
import hashlib
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time

from egosim.app.options import RunOptions
from egosim.app.runner import build_world
from egosim.bridge import HANDLERS, ClockMode, simulation_context
from egosim.world import World
from egosim.world.vehicle import ControlCommand, LongitudinalMode

TICK_S = 0.01
ROWS = ("gps", "imu", "lidar", "radar", "tf")
READINGS = "the ego's status and the object table"


def drive(world: World, tick: int, driving: bool) -> None:
    """Parked: no command (the ego stands). Driving: 8 m/s, the wheel swinging slowly."""
    if driving:
        steer = 0.05 * math.sin(0.5 * tick * TICK_S)
        world.egos[0].vehicle.command(
            ControlCommand(mode=LongitudinalMode.VELOCITY, velocity=8.0, front_steer=steer)
        )


def run(ticks: int, warmup: int, driving: bool) -> None:
    world = build_world(RunOptions(clock=ClockMode.SYNC))
    context = simulation_context(world, clock_mode=ClockMode.SYNC)
    spent: dict[str, list[float]] = {key: [] for key in (*ROWS, READINGS)}
    digests = {key: hashlib.sha256() for key in ROWS}
    for k in range(warmup + ticks):
        drive(world, k, driving)
        context.tick(TICK_S)
        with context.readings.publishing():
            began = time.thread_time()
            world.ego_status(0)
            context.objects()
            took = {READINGS: time.thread_time() - began}
            for key in ROWS:
                row = context.row(key)
                message_type = context.profile.message(row.type_name)
                began = time.thread_time()
                data = message_type.serialize(HANDLERS.publishers[key](context, row))
                took[key] = time.thread_time() - began
                digests[key].update(data)
        if k >= warmup:
            for key, seconds in took.items():
                spent[key].append(seconds)
    status = world.ego_status(0)
    print(
        f"{'driving' if driving else 'parked'}: {ticks} ticks, the ego at "
        f"{math.hypot(*status.velocity[:2]):.1f} m/s, yaw {status.pose.yaw:+.3f} rad"
    )
    for key in ROWS:
        rate = context.row(key).rate_hz or 0.0
        median = statistics.median(spent[key]) * 1e6
        print(
            f"  {context.row(key).name:10s} {median:7.1f} us per publish (median), "
            f"{min(spent[key]) * 1e6:7.1f} min, {median * rate * TICK_S:6.1f} us per tick "
            f"at {rate:g} Hz   bytes {digests[key].hexdigest()[:16]}"
        )
    print(f"  ({READINGS}: {statistics.median(spent[READINGS]) * 1e6:.1f} us per tick)")


FIRST_READINGS = """
import time
import numpy as np
from egosim.sensors import LidarModel, ObstacleBoxes, Pose
from egosim.sensors.radar import RadarModel
from egosim.world.traffic.objects import ObjectTable
began = time.perf_counter()
car = ObstacleBoxes(np.array([[10.0, 0.0, 0.8]]), np.array([[4.5, 1.9, 1.6]]), np.array([0.3]))
LidarModel().scan(Pose(), car)
scanned = time.perf_counter()
table = ObjectTable(
    unique_ids=np.array([2]), object_types=np.array([1]), names=("",),
    positions=np.array([[20.0, 0.0, 0.0]]), headings=np.zeros(1), velocities=np.zeros((1, 3)),
    accelerations=np.zeros((1, 3)), sizes=np.array([[4.5, 1.8, 1.5]]),
)
RadarModel().detect(Pose(), (0.0, 0.0, 0.0), 0.0, table)
print(f"first LiDAR scan {scanned - began:.2f} s, first radar detection "
      f"{time.perf_counter() - scanned:.2f} s")
"""


def first_start() -> None:
    with tempfile.TemporaryDirectory() as cache:
        for case in ("empty numba cache", "cache filled"):
            environment = {**os.environ, "NUMBA_CACHE_DIR": cache}
            result = subprocess.run(
                [sys.executable, "-c", FIRST_READINGS],
                env=environment,
                capture_output=True,
                text=True,
                check=True,
            )
            print(f"{case:18s} {result.stdout.strip()}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--ticks", type=int, default=1000)
    parser.add_argument("--warmup", type=int, default=200)
    parser.add_argument("--first-start", action="store_true")
    args = parser.parse_args()
    if args.first_start:
        first_start()
        return
    for driving in (False, True):
        run(args.ticks, args.warmup, driving)


if __name__ == "__main__":
    main()
