"""What one XML-RPC request costs the server: the embedded master's CPU per
`lookupService`, asked as rospy's non-persistent ServiceProxy asks it (a new
`xmlrpc.client.ServerProxy`, so a new HTTP connection, per call).

A subprocess serves `egosim.ros1.Master` with one registered service; this process makes
`--calls` lookups and the server reports its `time.process_time()` delta over them (its
every thread, user and kernel). With `--src DIR` given more than once, each round runs
one server per DIR (a checkout's `src`, put first on the server's path), the order
alternating from round to round, so two versions of the code can be compared on a
machine whose load drifts.

Usage: .venv/bin/python benchmarks/xmlrpc_lookup.py [--calls 3000] [--rounds 5]
           [--src OLD/src --src NEW/src]
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import time
import xmlrpc.client
from pathlib import Path

SERVICE = "/benchmark/lookup_me"

# The server: started on port 0, it prints its URI, then answers each line on stdin with
# its process CPU seconds so far; an empty line (end of input) stops it.
SERVER = f"""
import sys, time
from egosim.ros1 import Master
master = Master("http://127.0.0.1:0/").start()
master.register_service("/provider", {SERVICE!r}, "rosrpc://127.0.0.1:1/", "http://127.0.0.1:1/")
print(master.uri, flush=True)
for line in sys.stdin:
    print(time.process_time(), flush=True)
master.shutdown()
"""


class Server:
    def __init__(self, src: Path | None) -> None:
        path = [str(src)] if src is not None else []
        command = [sys.executable, "-c", f"import sys; sys.path[:0] = {path!r}\n{SERVER}"]
        self._process = subprocess.Popen(
            command, stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True
        )
        self.uri = self._read()

    def _read(self) -> str:
        assert self._process.stdout is not None
        line = self._process.stdout.readline()
        if not line:
            raise RuntimeError("the master process ended before answering")
        return line.strip()

    def cpu_s(self) -> float:
        assert self._process.stdin is not None
        self._process.stdin.write("cpu\n")
        self._process.stdin.flush()
        return float(self._read())

    def close(self) -> None:
        assert self._process.stdin is not None
        self._process.stdin.close()
        self._process.wait(timeout=30)


def lookups(uri: str, calls: int) -> None:
    for _ in range(calls):
        code, _message, _api = xmlrpc.client.ServerProxy(uri).lookupService("/client", SERVICE)
        assert code == 1


def measure(src: Path | None, calls: int) -> tuple[float, float]:
    """(server CPU µs, wall µs) per lookup."""
    server = Server(src)
    try:
        lookups(server.uri, 200)  # warm-up: handler threads started, code paths hot
        cpu_before = server.cpu_s()
        began = time.perf_counter()
        lookups(server.uri, calls)
        wall = time.perf_counter() - began
        cpu = server.cpu_s() - cpu_before
    finally:
        server.close()
    return cpu * 1e6 / calls, wall * 1e6 / calls


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--calls", type=int, default=3000)
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--src", type=Path, action="append", help="a checkout's src directory")
    args = parser.parse_args()
    sources: list[Path | None] = list(args.src) if args.src else [None]
    results: dict[Path | None, list[tuple[float, float]]] = {src: [] for src in sources}
    for round_ in range(args.rounds):
        order = sources if round_ % 2 == 0 else sources[::-1]
        for src in order:
            cpu_us, wall_us = measure(src, args.calls)
            results[src].append((cpu_us, wall_us))
            print(
                f"round {round_ + 1} {src or 'installed'}: server CPU {cpu_us:.0f} µs, "
                f"wall {wall_us:.0f} µs per lookup",
                flush=True,
            )
    for src, rows in results.items():
        cpus = [cpu for cpu, _ in rows]
        print(
            f"{src or 'installed'}: server CPU per lookup median {statistics.median(cpus):.0f} µs"
            f" (range {min(cpus):.0f}-{max(cpus):.0f}), wall median "
            f"{statistics.median(wall for _, wall in rows):.0f} µs over {len(rows)} rounds"
        )


if __name__ == "__main__":
    main()
