"""How long `egosim run` takes to stop after Ctrl-C / SIGTERM (the goal is under 2 s).

Starts the simulator (town, default scenario, embedded master), waits for
"egosim: ready", sends the signal and times the exit, several times per signal.

Usage: .venv/bin/python benchmarks/shutdown.py [--runs 5]
"""

from __future__ import annotations

import argparse
import os
import signal
import statistics
import subprocess
import sys
import time

from loopback import free_port


def time_stop(stop_signal: signal.Signals) -> float:
    env = dict(os.environ, ROS_MASTER_URI=f"http://127.0.0.1:{free_port()}/", ROS_IP="127.0.0.1")
    process = subprocess.Popen(
        [sys.executable, "-m", "egosim", "run", "--log-level", "WARNING"],
        env=env,
        stdout=subprocess.PIPE,
        text=True,
    )
    assert process.stdout is not None
    for line in process.stdout:
        if line.strip() == "egosim: ready":
            break
    time.sleep(1.0)
    started = time.monotonic()
    process.send_signal(stop_signal)
    code = process.wait(timeout=30)
    elapsed = time.monotonic() - started
    if code != 0:
        raise SystemExit(f"egosim exited with {code} after {stop_signal.name}")
    return elapsed


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--runs", type=int, default=5)
    args = parser.parse_args()
    for stop_signal in (signal.SIGINT, signal.SIGTERM):
        times = [time_stop(stop_signal) for _ in range(args.runs)]
        print(
            f"{stop_signal.name}: median {statistics.median(times) * 1e3:.0f} ms, "
            f"max {max(times) * 1e3:.0f} ms over {args.runs} runs"
        )


if __name__ == "__main__":
    main()
