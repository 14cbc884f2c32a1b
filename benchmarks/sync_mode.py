"""Synchronous-mode throughput: ticks per second of `egosim run --clock sync`, publishing.

Starts the simulator (town map, default scenario, 100 Hz physics: 10 ms ticks) as a
subprocess, subscribes to every published row (so every builder runs, the LiDAR
included), to the `--topics` named, or with `--driving-stack` to the rows a driving stack
reads (DRIVING_STACK_ROWS: the ego, the objects around it, the traffic light, collisions
and /clock, which a ROS node on simulation time reads), starts sync mode and times
WaitForTick calls of `--ticks-per-call` ticks each; with `--ctrl-cmd`, each call is
preceded by a SyncModeCtrlCmd for its first frame, as a driving client's loop does.
Real-time factor =
simulated seconds / wall seconds. Beside each figure, the CPU time per tick (Linux's
/proc): the simulator's loop thread, its other threads (TCPROS writers, XML-RPC, the
embedded master) and the client's process, so where a tick's wall time goes shows.

With `--rounds N`, each setting is timed N times in turn on the same simulator, then the
best round of each is printed again (the figure that a busy machine disturbs least).

Usage: .venv/bin/python benchmarks/sync_mode.py [--ticks 2000] [--ticks-per-call 1 100]
       [--rounds 1] [--topics /Ego_topic /Object_topic ... | --driving-stack] [--ctrl-cmd]
"""

from __future__ import annotations

import argparse
import os
import resource
import subprocess
import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass

from loopback import free_port, start_simulator

from egosim.bridge.protocol.network import default_network_settings
from egosim.bridge.protocol.table import Direction
from egosim.msgs import Profile, ServiceType, get_profile
from egosim.ros1 import Node

TICK_MS = 10
USER = "benchmark"
DRIVING_STACK_ROWS = (
    "/Ego_topic",
    "/Object_topic",
    "/GetTrafficLightStatus",
    "/CollisionData",
    "/clock",
)


class Counter:
    def __init__(self) -> None:
        self.count = 0
        self.lock = threading.Lock()

    def __call__(self, data: bytes, header: object) -> None:
        with self.lock:
            self.count += 1


@contextmanager
def simulator_client(name: str) -> Iterator[tuple[Node, subprocess.Popen[str]]]:
    """`egosim run --clock sync` as a subprocess, and a node `name` on its master."""
    master_uri = f"http://127.0.0.1:{free_port()}/"
    simulator = start_simulator("--clock", "sync", master_uri=master_uri)
    try:
        with Node(name, master_uri=master_uri, rosout_logger=None) as node:
            yield node, simulator
    finally:
        simulator.terminate()
        simulator.wait(10)


def process_cpu(pid: int) -> tuple[float, float]:
    """CPU seconds (user + system) of process `pid`'s main thread and of its other
    threads, from /proc (threads that ended are counted with the process's own total)."""
    ticks = os.sysconf("SC_CLK_TCK")

    def cpu(stat_path: str) -> float:
        with open(stat_path) as stat:
            fields = stat.read().rpartition(")")[2].split()
        return (int(fields[11]) + int(fields[12])) / ticks  # utime, stime

    whole = cpu(f"/proc/{pid}/stat")
    main = cpu(f"/proc/{pid}/task/{pid}/stat")
    return main, whole - main


def own_cpu() -> float:
    """CPU seconds (user + system) of this process, every thread."""
    usage = resource.getrusage(resource.RUSAGE_SELF)
    return usage.ru_utime + usage.ru_stime


def start_sync_mode(node: Node, profile: Profile) -> int:
    """Start sync mode as USER with TICK_MS ticks; the current frame."""
    command = profile.service("morai_msgs/MoraiSyncModeCmdSrv")
    start = command.request.new(
        request=profile.message("morai_msgs/SyncModeCmd").new(
            user_id=USER, start_sync_mode=True, time_step=TICK_MS
        )
    )
    call = node.service_proxy("/SyncModeCmd", command).call(command.request.serialize(start))
    return int(command.response.deserialize(call).response.frame)


def control_request(profile: Profile, control: ServiceType, frame: int) -> bytes:
    """A SyncModeCtrlCmd holding 20 km/h from `frame` on."""
    command = profile.message("morai_msgs/CtrlCmd").new(longlCmdType=2, velocity=20.0)
    request = profile.message("morai_msgs/SyncModeCtrlCmd").new(frame=frame, command=command)
    return control.request.serialize(control.request.new(request=request))


@dataclass(frozen=True)
class Round:
    """One timed run of WaitForTick calls: ticks, wall seconds and CPU seconds."""

    per_call: int
    ticks: int
    wall: float
    loop_cpu: float
    others_cpu: float
    client_cpu: float

    def __str__(self) -> str:
        per_tick = 1e6 / self.ticks
        return (
            f"{self.per_call:4d} ticks per WaitForTick: {self.ticks / self.wall:7.0f} ticks/s, "
            f"{self.ticks * TICK_MS / 1000 / self.wall:5.1f}x real time; per tick "
            f"{self.wall * per_tick:.0f} us wall, CPU: simulator loop thread "
            f"{self.loop_cpu * per_tick:.0f} us, its other threads "
            f"{self.others_cpu * per_tick:.0f} us, client {self.client_cpu * per_tick:.0f} us"
        )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--ticks", type=int, default=2000)
    parser.add_argument("--ticks-per-call", type=int, nargs="+", default=[1, 100])
    parser.add_argument(
        "--rounds", type=int, default=1, help="time each setting this many times, then the best"
    )
    rows = parser.add_mutually_exclusive_group()
    rows.add_argument(
        "--topics", nargs="*", help="subscribe to these rows only (default: every one)"
    )
    rows.add_argument(
        "--driving-stack",
        dest="topics",
        action="store_const",
        const=list(DRIVING_STACK_ROWS),
        help=f"subscribe to a driving stack's rows only: {' '.join(DRIVING_STACK_ROWS)}",
    )
    parser.add_argument(
        "--ctrl-cmd", action="store_true", help="send a SyncModeCtrlCmd before each call"
    )
    args = parser.parse_args()

    profile = get_profile("26.r1")
    with simulator_client("sync_benchmark") as (node, simulator):
        counters = {}
        for row in default_network_settings().enabled_rows():
            wanted = args.topics is None or row.name in args.topics
            if row.direction is Direction.PUBLISH and wanted:
                counters[row.name] = Counter()
                node.subscribe(row.name, profile.message(row.type_name), counters[row.name])
        time.sleep(1.0)  # let every subscription connect before the clock starts
        tick = profile.service("morai_msgs/MoraiWaitForTickSrv")
        frame = start_sync_mode(node, profile)
        proxy = node.service_proxy("/SyncModeWaitForTick", tick, persistent=True)
        control = profile.service("morai_msgs/MoraiSyncModeCtrlCmdSrv")
        control_proxy = node.service_proxy("/SyncModeCtrlCmd", control, persistent=True)
        subscribed = "every published row" if args.topics is None else " ".join(counters)
        print(f"town + default scenario, {TICK_MS} ms ticks, subscribed: {subscribed}")
        best: dict[int, Round] = {}
        for _ in range(args.rounds):
            for per_call in args.ticks_per_call:
                calls = max(args.ticks // per_call, 1)
                began = time.perf_counter()
                loop_began, others_began = process_cpu(simulator.pid)
                client_began = own_cpu()
                for _ in range(calls):
                    if args.ctrl_cmd:
                        control_proxy.call(control_request(profile, control, frame + 1))
                    frame += per_call
                    request = tick.request.new(
                        request=profile.message("morai_msgs/WaitForTick").new(
                            user_id=USER, frame=frame
                        )
                    )
                    tick.response.deserialize(proxy.call(tick.request.serialize(request)))
                wall = time.perf_counter() - began
                loop_cpu, others_cpu = process_cpu(simulator.pid)
                timed = Round(
                    per_call,
                    calls * per_call,
                    wall,
                    loop_cpu - loop_began,
                    others_cpu - others_began,
                    own_cpu() - client_began,
                )
                print(timed)
                if per_call not in best or timed.wall < best[per_call].wall:
                    best[per_call] = timed
        if args.rounds > 1:
            print(f"best of {args.rounds} rounds:")
            for timed in best.values():
                print(timed)
        received = ", ".join(f"{name} {c.count}" for name, c in sorted(counters.items()))
        print(f"messages received: {received}")


if __name__ == "__main__":
    main()
