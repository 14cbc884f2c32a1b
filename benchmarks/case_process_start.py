"""What starting a case's process with default signal handling costs: the median wall
time from start to exit, and the CPU time (user + system) per start, of a process that
does nothing (`/bin/true`) and of a shell (`/bin/sh -c true`, as a stack is run), each
started directly and through egosim/batch/default_signals.py, as GroupProcess starts them.
On a loaded machine read the CPU time: the wall time is mostly waiting for a core.

Usage: .venv/bin/python benchmarks/case_process_start.py [--runs N]
"""

from __future__ import annotations

import argparse
import resource
import statistics
import subprocess
import sys
import time

from egosim.batch.processes import DEFAULT_SIGNALS

PROGRAMS = {"/bin/true": ["/bin/true"], "/bin/sh -c true": ["/bin/sh", "-c", "true"]}


def start_ms(args: list[str], runs: int) -> tuple[float, float]:
    """(median wall ms, mean CPU ms) of starting `args` and waiting for its exit."""
    times = []
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    for _ in range(runs):
        start = time.perf_counter()
        subprocess.run(args, check=True)
        times.append(time.perf_counter() - start)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return statistics.median(times) * 1000.0, cpu / runs * 1000.0


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--runs", type=int, default=50)
    runs = parser.parse_args().runs
    launcher = [sys.executable, "-I", "-S", str(DEFAULT_SIGNALS)]
    print("| program | direct: wall, CPU | through default_signals: wall, CPU |")
    print("|---|---:|---:|")
    for name, args in PROGRAMS.items():
        direct, launched = start_ms(args, runs), start_ms([*launcher, *args], runs)
        print(
            f"| {name} | {direct[0]:.1f} ms, {direct[1]:.1f} ms "
            f"| {launched[0]:.1f} ms, {launched[1]:.1f} ms |"
        )


if __name__ == "__main__":
    main()
