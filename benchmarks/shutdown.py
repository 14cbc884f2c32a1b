"""How long `egosim run` takes to stop after Ctrl-C / SIGTERM (the goal is under 2 s).

Starts the simulator (town, default scenario, embedded master), waits for
"egosim: ready", sends the signal and times the exit, several times per signal.

Usage: .venv/bin/python benchmarks/shutdown.py [--runs 5]
"""

from __future__ import annotations

import argparse
import signal
import statistics
import time

from loopback import start_simulator


def time_stop(stop_signal: signal.Signals) -> float:
    process = start_simulator()
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
