"""Synchronous-mode throughput: ticks per second of `egosim run --clock sync`, publishing.

Starts the simulator (town map, default scenario, 100 Hz physics: 10 ms ticks) as a
subprocess, subscribes to every published row (so every builder runs, the LiDAR
included) or to the `--topics` named, starts sync mode and times WaitForTick calls of
`--ticks-per-call` ticks each; with `--ctrl-cmd`, each call is preceded by a
SyncModeCtrlCmd for its first frame, as a driving client's loop does. Real-time factor =
simulated seconds / wall seconds.

Usage: .venv/bin/python benchmarks/sync_mode.py [--ticks 2000] [--ticks-per-call 1 100]
       [--topics /Ego_topic /Object_topic ...] [--ctrl-cmd]
"""

from __future__ import annotations

import argparse
import subprocess
import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager

from loopback import free_port, start_simulator

from egosim.bridge.protocol.network import default_network_settings
from egosim.bridge.protocol.table import Direction
from egosim.msgs import Profile, ServiceType, get_profile
from egosim.ros1 import Node

TICK_MS = 10
USER = "benchmark"


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


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--ticks", type=int, default=2000)
    parser.add_argument("--ticks-per-call", type=int, nargs="+", default=[1, 100])
    parser.add_argument(
        "--topics", nargs="*", help="subscribe to these rows only (default: every one)"
    )
    parser.add_argument(
        "--ctrl-cmd", action="store_true", help="send a SyncModeCtrlCmd before each call"
    )
    args = parser.parse_args()

    profile = get_profile("26.r1")
    with simulator_client("sync_benchmark") as (node, _):
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
        for per_call in args.ticks_per_call:
            calls = max(args.ticks // per_call, 1)
            began = time.perf_counter()
            for _ in range(calls):
                if args.ctrl_cmd:
                    control_proxy.call(control_request(profile, control, frame + 1))
                frame += per_call
                request = tick.request.new(
                    request=profile.message("morai_msgs/WaitForTick").new(user_id=USER, frame=frame)
                )
                tick.response.deserialize(proxy.call(tick.request.serialize(request)))
            wall = time.perf_counter() - began
            ticks = calls * per_call
            print(
                f"{per_call:4d} ticks per WaitForTick: {ticks / wall:7.0f} ticks/s, "
                f"{ticks * TICK_MS / 1000 / wall:5.1f}x real time"
            )
        received = ", ".join(f"{name} {c.count}" for name, c in sorted(counters.items()))
        print(f"messages received: {received}")


if __name__ == "__main__":
    main()
