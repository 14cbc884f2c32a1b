"""What the message profiles cost a new egosim process: each in a fresh interpreter,
the CPU time of `get_profile(release)` (its thread's: numpy's OpenBLAS threads spin
for a while after the import; egosim.msgs imported first, not timed); the
import time of `egosim.batch.worker` (`-X importtime`, the sum of every module's own
time); and the CPU time (user + system) of a process that imports it, builds the three
profiles and looks up every release of each type a default `egosim run` binds (its
enabled rows' types, as the bridge's `releases_of` / `service_releases_of` do, with the
default release's type, which the bridge advertises), that part alone, and which typed
modules (egosim.msgs.typed, for the type checker) it imported.

Run it with bytecode cached, as a user's machine has it: each command runs once before
it is timed.

Usage: env -u PYTHONDONTWRITEBYTECODE .venv/bin/python benchmarks/profile_start.py [--runs 7]
"""

from __future__ import annotations

import argparse
import functools
import os
import resource
import statistics
import subprocess
import sys
from collections.abc import Callable

from egosim.msgs import PROFILES

PROFILE_CPU = """
import sys, time
from egosim.msgs import get_profile
start = time.thread_time()
get_profile(sys.argv[1])
print(time.thread_time() - start)
"""

BOUND_TYPES = """
import sys, time

from egosim.batch import worker
from egosim.bridge.protocol.network import default_network_settings
from egosim.bridge.protocol.releases import releases_of, service_releases_of
from egosim.bridge.protocol.table import Direction
from egosim.msgs import PROFILES, get_profile

from egosim.msgs import profile

parse = profile.get_types_from_msg
parsed = []
profile.get_types_from_msg = lambda text, name: parsed.append(name) or parse(text, name)
start = time.thread_time()
for name in PROFILES:
    get_profile(name)
for row in default_network_settings().enabled_rows():
    if row.direction is Direction.SERVICE:
        service_releases_of(row.type_name, PROFILES[0])[0].service_type
    else:
        releases_of(row.type_name, PROFILES[0])[0].message_type
print(time.thread_time() - start)
print(len(parsed))
typed = sorted(name for name in sys.modules if name.startswith("egosim.msgs.typed."))
print(", ".join(typed) or "none")
"""


def python(*args: str) -> list[str]:
    return [sys.executable, *args]


def bound_types() -> tuple[float, float, int, str]:
    """The bound-types process's CPU time (interpreter start included), the CPU time of its
    profiles and look-ups alone, how many definitions it parsed (of each release whose
    types it built), and the typed modules (egosim.msgs.typed) it imported."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    command = python("-c", BOUND_TYPES)
    out = subprocess.run(command, check=True, capture_output=True, text=True).stdout
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    whole = after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime
    part, parsed, typed = out.splitlines()
    return whole, float(part), int(parsed), typed


def profile_cpu_s(release: str) -> float:
    command = python("-c", PROFILE_CPU, release)
    return float(subprocess.run(command, check=True, capture_output=True, text=True).stdout)


def import_time_s() -> float:
    """The sum of every module's own import time (µs in importtime's second column)."""
    command = python("-X", "importtime", "-c", "import egosim.batch.worker")
    lines = subprocess.run(command, check=True, capture_output=True, text=True).stderr
    own_us = [
        int(line.split("|")[0].split(":")[1])
        for line in lines.splitlines()
        if line.startswith("import time:") and line.split("|")[0].split(":")[1].strip().isdigit()
    ]
    return sum(own_us) / 1e6


def median_and_best(runs: int, measure: Callable[[], float]) -> str:
    measure()  # bytecode written, caches warm
    times = [measure() for _ in range(runs)]
    return spread(times)


def spread(times: list[float]) -> str:
    """Median and best of `times` (s), in ms: on a shared machine the best is the cost."""
    return f"median {statistics.median(times) * 1000:.0f} ms, best {min(times) * 1000:.0f} ms"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=7)
    runs = parser.parse_args().runs
    if os.environ.get("PYTHONDONTWRITEBYTECODE"):
        print("warning: PYTHONDONTWRITEBYTECODE is set, every import compiles its source")
    print(f"load average: {os.getloadavg()[0]:.1f}; {runs} fresh processes each")
    for release in PROFILES:
        cpu = median_and_best(runs, functools.partial(profile_cpu_s, release))
        print(f"get_profile({release!r}), CPU: {cpu}")
    print(f"import egosim.batch.worker (-X importtime): {median_and_best(runs, import_time_s)}")
    bound_types()  # bytecode written, caches warm
    bound = [bound_types() for _ in range(runs)]
    print("a process importing it, three profiles, the bound types' releases, CPU:")
    print(f"  the process: {spread([run[0] for run in bound])}")
    print(f"  the profiles and the releases' look-ups: {spread([run[1] for run in bound])}")
    print(f"  definitions parsed: {bound[0][2]}; typed modules imported: {bound[0][3]}")
    print(f"load average after: {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
