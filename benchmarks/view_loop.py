"""What the live view costs the simulation: loop step time with 0, 1 and 10 browsers,
the server's CPU per browser, and the bytes of a frame and of the map.

The town with its default scenario runs on a real-time loop (100 Hz) in this process,
with the view's stage after every step and the view's server on its thread, as
`egosim run` has them (the ROS side is left out: it costs the same with or without
browsers, and leaving it out makes the view's share look larger, not smaller).
Browsers are websocket clients in a child process that read every frame sent.
Configurations are interleaved and repeated; medians are reported.

First, the loop thread's own share, free of thread and machine noise: the minimum
time of taking one frame against the minimum time of one step.

Run: .venv/bin/python benchmarks/view_loop.py [--seconds 8] [--repeats 3] [--samples 300]
"""

from __future__ import annotations

import argparse
import gzip
import os
import resource
import statistics
import subprocess
import sys
import threading
import time

from websocket_browsers import SCRIPT as BROWSERS_SCRIPT

from egosim.app.inbox import Inbox
from egosim.app.loop import SimulationLoop
from egosim.bridge import BridgeContext, simulation_context
from egosim.view.controls import ViewControls
from egosim.view.hub import MAX_FRAME_RATE_HZ, FrameHub
from egosim.view.server import ViewBackend, ViewServer
from egosim.view.snapshot import FrameInfo, capture_frame, encode, map_snapshot
from egosim.view.stage import ViewStage
from egosim.world import World
from egosim.world.map import build_builtin_map
from egosim.world.scenario import load_default_scenario

DT = 0.01
CLIENTS = (0, 1, 10)
#: A configuration with frames taken at the full rate but no browser: the loop's own share.
CAPTURE_ONLY = -1


class TimedStep:
    """The loop's step (world step + view stage), timed on the loop thread."""

    def __init__(self, context: BridgeContext, stage: ViewStage) -> None:
        self.context = context
        self.stage = stage
        self.durations: list[float] = []
        self.cpu_durations: list[float] = []
        self.thread_cpu = 0.0

    def __call__(self) -> None:
        start, cpu_start = time.perf_counter(), time.thread_time()
        self.context.world.step(DT)
        self.stage.after_step()
        self.thread_cpu = time.thread_time()
        self.durations.append(time.perf_counter() - start)
        self.cpu_durations.append(self.thread_cpu - cpu_start)

    def mark(self) -> None:
        """Start counting the loop thread's CPU (on that thread)."""
        self.thread_cpu = self.thread_cpu_start = time.thread_time()


def process_cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_SELF)
    return usage.ru_utime + usage.ru_stime


def measure(clients: int, seconds: float, frame_sizes: list[int]) -> dict[str, float]:
    world = World(build_builtin_map("town"), load_default_scenario())
    context = simulation_context(world)
    hub = FrameHub()
    controls = ViewControls(context, None)
    stage = ViewStage(context, hub, controls, "real")
    backend = ViewBackend(
        hub=hub,
        inbox=Inbox(),
        prepare=controls.prepare,
        apply=controls.apply,
        capture=stage.capture,
        history=lambda: encode(stage.history.message()),
        map_json=lambda: encode(map_snapshot(world.map)),
        system_state=lambda: ([], [], []),
        hello={"type": "hello", "clock_mode": "real"},
    )
    server = ViewServer(backend, "127.0.0.1", 0, readonly=False)
    server.start()
    browsers = None
    if clients == CAPTURE_ONLY:
        hub.clients = 1  # frames are due, but nobody reads them
    elif clients:
        browsers = subprocess.Popen(
            [
                sys.executable,
                str(BROWSERS_SCRIPT),
                f"ws://127.0.0.1:{server.port}/ws",
                str(clients),
                str(seconds + 3.0),
            ]
        )
        deadline = time.monotonic() + 15.0
        while hub.clients < clients:
            if time.monotonic() > deadline:
                raise RuntimeError(f"only {hub.clients} of {clients} browsers connected")
            time.sleep(0.05)
    step = TimedStep(context, stage)
    stop = threading.Event()
    loop = SimulationLoop(step, backend.inbox, DT, 1.0, stop, round(seconds / DT))
    thread = threading.Thread(target=lambda: (step.mark(), loop.run()))
    cpu0 = process_cpu()
    wall0 = time.monotonic()
    thread.start()
    thread.join()
    wall = time.monotonic() - wall0
    cpu = process_cpu() - cpu0
    latest = hub.latest()
    if latest is not None:
        frame_sizes.append(len(latest[1].encode()))
    server.close()
    if browsers is not None:
        browsers.wait(30)
    return {
        "step_ms": 1000 * statistics.fmean(step.durations),
        "step_cpu_ms": 1000 * statistics.fmean(step.cpu_durations),
        "other_threads_cpu_percent": 100 * (cpu - (step.thread_cpu - step.thread_cpu_start)) / wall,
    }


def loop_share(samples: int) -> None:
    """What taking a frame costs the loop thread, against what a step costs: minima of
    many tries on the first seconds of the scenario, i.e. on a quiet core."""
    world = World(build_builtin_map("town"), load_default_scenario())
    context = simulation_context(world)
    info = FrameInfo("real", 1.0, True)
    steps, captures = [], []
    for _ in range(samples):
        start = time.perf_counter()
        for _ in range(10):
            world.step(DT)
        steps.append((time.perf_counter() - start) / 10)
        start = time.perf_counter()
        for _ in range(10):
            capture_frame(context, info)
        captures.append((time.perf_counter() - start) / 10)
    capture, step = min(captures), min(steps)
    print(
        f"one frame taken: {1e6 * capture:.0f} us; one step: {1e3 * step:.3f} ms (minima of "
        f"{samples}); at {MAX_FRAME_RATE_HZ:.0f} frames/s on a {1 / DT:.0f} Hz loop: "
        f"{100 * capture * MAX_FRAME_RATE_HZ * DT / step:.1f}% of the step time"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=8.0)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--samples", type=int, default=300)
    args = parser.parse_args()
    loop_share(args.samples)
    if args.repeats == 0:
        return
    configurations = (CLIENTS[0], CAPTURE_ONLY, *CLIENTS[1:])
    results: dict[int, list[dict[str, float]]] = {n: [] for n in configurations}
    frame_sizes: list[int] = []
    for _ in range(args.repeats):
        for n in configurations:
            results[n].append(measure(n, args.seconds, frame_sizes))
    base_step = statistics.median(r["step_ms"] for r in results[0])
    base_cpu = statistics.median(r["other_threads_cpu_percent"] for r in results[0])
    print(
        f"real-time loop at {1 / DT:.0f} Hz, {args.seconds:.0f} s x {args.repeats}, medians; "
        f"load average {os.getloadavg()[0]:.1f}"
    )
    base_cpu_step = statistics.median(r["step_cpu_ms"] for r in results[0])
    print(
        f"{'browsers':>8}{'step ms':>10}{'vs none':>9}{'step CPU ms':>13}{'vs none':>9}"
        f"{'server CPU %':>14}{'per browser':>13}"
    )
    for n in configurations:
        step_ms = statistics.median(r["step_ms"] for r in results[n])
        step_cpu = statistics.median(r["step_cpu_ms"] for r in results[n])
        cpu = statistics.median(r["other_threads_cpu_percent"] for r in results[n]) - base_cpu
        per = f"{cpu / n:.2f}" if n > 0 else "-"
        name = "capture" if n == CAPTURE_ONLY else str(n)
        print(
            f"{name:>8}{step_ms:>10.3f}{100 * (step_ms / base_step - 1):>8.1f}%"
            f"{step_cpu:>13.3f}{100 * (step_cpu / base_cpu_step - 1):>8.1f}%{cpu:>14.2f}{per:>13}"
        )
    world_map = build_builtin_map("town")
    map_text = encode(map_snapshot(world_map)).encode()
    print(f"frame: {statistics.median(frame_sizes):.0f} bytes (median of {len(frame_sizes)})")
    zipped = len(gzip.compress(map_text, 6))
    print(f"map: {len(map_text)} bytes, {zipped} gzipped (once per browser)")


if __name__ == "__main__":
    main()
