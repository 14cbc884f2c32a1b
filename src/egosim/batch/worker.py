"""A batch's simulator worker: `python -m egosim.batch.worker`, kept warm by one worker
slot of the batch (warm_simulator) and running its cases one after another.

What a case would pay for in a process of its own, a worker pays for once: starting
Python, importing egosim, numpy and rosbags, the message types, each map and its camera
scene (kept: they are immutable), the cameras' OpenGL context. Everything a case can
change is made anew for it, as `egosim run` makes it (its ROS master, on a new port, is
its supervisor's: case_runner): the node and every topic and service, the world and
its random generator (the scenario's seed), the clock, sync mode, replay, sensors, ego
sessions, the recorder and its bag, the drive's evaluation. Between cases the worker
puts back what a run changes in the process (environment, working folder, log throttles)
and checks that the case left nothing behind: a thread or socket still open after it
(which a later case, or its stack, could meet) makes the worker leave, and its slot
starts a fresh one.

The lines it reads and writes are in worker_protocol. SIGINT or SIGTERM end the case
running now (scored) and then the worker.
"""

from __future__ import annotations

import os
import queue
import signal
import sys
import threading
import time
import traceback
from pathlib import Path
from typing import BinaryIO

from egosim.batch.simulate import simulate_case
from egosim.batch.worker_protocol import RUN, Command, case_line, done_line, parse_command
from egosim.logthrottle import forget_every_window
from egosim.render import open_renderer
from egosim.sensors.camera_render import CameraRenderer

LINGER_S = 5.0
"""How long a finished case's threads may take to end."""
EXIT_FAILED = 1
"""A case whose run raised, as a process dying of it would exit."""
POLL_S = 0.2
WORKER_LINE = "egosim batch worker"
"""Begins the first line of a case's simulator.log: which worker ran it, its how-manieth."""


class SharedRenderer:
    """The cameras' engine, opened by the first case that renders and kept for the next:
    one OpenGL context per worker (each costs 0.1 s and some memory never given back).
    It renders what each request asks, nothing of an earlier one."""

    def __init__(self) -> None:
        self._renderer: CameraRenderer | None = None
        self.sockets: frozenset[str] = frozenset()
        """Sockets its driver opened (not a case's)."""

    def open(self) -> CameraRenderer:
        if self._renderer is None:
            before = open_sockets()
            self._renderer = open_renderer()  # not kept when it fails: tried (and logged) again
            self.sockets = frozenset(open_sockets() - before)
        return self._renderer


def open_sockets() -> set[str]:
    """The process's open sockets, as /proc names them (`socket:[INODE]`)."""
    found = set()
    for fd in os.listdir("/proc/self/fd"):
        try:
            target = os.readlink(f"/proc/self/fd/{fd}")
        except OSError:  # closed meanwhile (the listing's own descriptor)
            continue
        if target.startswith("socket:"):
            found.add(target)
    return found


class Worker:
    def __init__(self) -> None:
        self.home = Path.cwd()
        self.environment = dict(os.environ)
        self.renderer = SharedRenderer()
        self.leaving = threading.Event()
        self._current: threading.Event | None = None
        self._threads: set[threading.Thread] = set()
        self._sockets: set[str] = set()
        self.cases = 0

    def settle(self) -> None:
        """What the worker itself runs: a case must leave no thread or socket beyond."""
        self._threads = set(threading.enumerate())
        self._sockets = open_sockets()

    def stop_case(self) -> None:
        current = self._current
        if current is not None:
            current.set()

    def leave(self) -> None:
        """End the case running now, then the worker."""
        self.leaving.set()
        self.stop_case()

    def run(self, command: Command) -> bool:
        """Run one case; whether the worker may run another."""
        case_dir = command.case_dir
        print(case_line(case_dir), flush=True)
        self.cases += 1
        print(f"{WORKER_LINE} {os.getpid()}: case {self.cases} in this process", flush=True)
        stop = threading.Event()
        self._current = stop
        if self.leaving.is_set():
            stop.set()
        forget_every_window()
        failed = False
        try:
            os.chdir(case_dir)
            status = simulate_case(case_dir, command.master_uri, stop, self.renderer.open)
        except Exception:
            traceback.print_exc()
            status, failed = EXIT_FAILED, True
        finally:
            self._current = None
            os.chdir(self.home)
            os.environ.clear()
            os.environ.update(self.environment)
        leftovers = self._leftovers()
        if leftovers:
            print(f"egosim batch worker: left running after the case: {leftovers}; replaced")
        last = failed or bool(leftovers) or self.leaving.is_set()
        print(done_line(status, last), flush=True)
        return not last

    def _leftovers(self) -> str:
        """What the case left running (after up to LINGER_S), '' if nothing."""
        deadline = time.monotonic() + LINGER_S
        while True:
            threads = [t for t in threading.enumerate() if t not in self._threads]
            sockets = open_sockets() - self._sockets - self.renderer.sockets
            if not threads and not sockets:
                return ""
            if time.monotonic() >= deadline:
                names = ", ".join(t.name for t in threads)
                return f"{len(threads)} threads ({names}), {len(sockets)} sockets"
            time.sleep(0.05)


def read_commands(stream: BinaryIO, worker: Worker, cases: queue.Queue[Command | None]) -> None:
    """The supervisor's commands: cases to run are queued, `stop` ends the one running;
    the end of input ends the worker."""
    for raw in stream:
        try:
            command = parse_command(raw.decode("utf-8", "replace"))
        except ValueError as error:
            print(f"egosim batch worker: {error}", file=sys.stderr, flush=True)
            continue
        if command.kind == RUN:
            cases.put(command)
        else:
            worker.stop_case()
    worker.leave()
    cases.put(None)


def main() -> int:
    worker = Worker()
    cases: queue.Queue[Command | None] = queue.Queue()
    reader = threading.Thread(
        target=read_commands, args=(sys.stdin.buffer, worker, cases), name="commands", daemon=True
    )
    reader.start()
    worker.settle()
    for number in (signal.SIGINT, signal.SIGTERM):
        signal.signal(number, lambda *_: worker.leave())
    while not worker.leaving.is_set():
        try:
            command = cases.get(timeout=POLL_S)
        except queue.Empty:
            continue
        if command is None or not worker.run(command):
            break
    return 0


if __name__ == "__main__":
    status = main()
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(status)  # a case's thread left behind must not hold the exit
