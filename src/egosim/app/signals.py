"""How a run stops: SIGINT, SIGTERM, SIGHUP, `rosnode kill` or the caller ask for a clean
stop; a second signal, or a clean stop that overruns its deadline, ends the process at once
with the bag closed.

Signals are read by a watcher thread from the interpreter's wakeup file descriptor, and the
Python-level handlers do nothing. A handler runs on the main thread, between two of its
bytecodes: wherever the main thread happens to be (inside a lock, a queue, the stop
event's own lock, a wait that the handler cannot end). A handler that takes a lock there
can deadlock, and one that needs the main thread to move on waits as long as the main
thread is stuck. The watcher needs nothing from the main thread, so a stop is seen, and a
forced exit happens, whatever the main thread is doing (short of a C call that holds the
interpreter lock all along: then no Python thread runs at all).
"""

from __future__ import annotations

import contextlib
import faulthandler
import logging
import os
import signal
import socket
import sys
import threading
import time
from collections.abc import Callable, Iterator
from typing import NoReturn

from .exit_codes import EXIT_STOP_FORCED

log = logging.getLogger(__name__)

#: Ctrl-C, `kill`, and the terminal going away (a closed window, a dropped SSH session):
#: each stops cleanly, so the bag is closed.
STOP_SIGNALS = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)
#: A clean stop not done this long after it began is forced (s): the documented bound on a
#: stop is 2 s, and the forced exit needs the rest.
CLEAN_STOP_DEADLINE_S = 1.4
#: How long a forced exit gives each closer (the bag's writer: what is queued and the
#: index), and then the report of why it exits (s).
FORCED_CLOSE_S = 0.3
FORCED_REPORT_S = 0.1
#: The byte `request` writes to wake the watcher (no signal has the number 0).
_WAKE = 0

Closer = Callable[[float], object]
"""Closes something within the given seconds (the bag: writes what is queued and the index)."""


class StopControl:
    """The stop requests of one run, seen by a watcher thread (see the module docstring).

    The first request (a signal, or `request` from any thread) keeps its reason and sets
    `stop`. A second signal forces the exit: every closer runs (the bag gets its index),
    then the process exits with 128 + the signal's number. With `deadline_s`, a clean stop
    not `done` that long after it began is forced too, after logging every thread's stack
    (exit status EXIT_STOP_FORCED). A stop begins when it is asked for (during start-up
    too: the run then stops after the step it is in), or when the loop ends by itself (a
    --duration run).
    """

    def __init__(
        self,
        stop: threading.Event,
        deadline_s: float | None = None,
        exit_process: Callable[[int], object] = os._exit,
    ) -> None:
        self.stop = stop
        self.deadline_s = deadline_s
        self.reason: str | None = None
        self._exit_process = exit_process
        self._closers: list[Closer] = []
        self._lock = threading.Lock()
        self._began: float | None = None
        self._signals = 0
        self._done = False
        self._read, self._write = socket.socketpair()
        self._write.setblocking(False)
        self._watcher = threading.Thread(target=self._watch, name="stop watcher", daemon=True)

    # -- what the run tells it (any thread) -------------------------------------------

    def request(self, reason: str) -> None:
        """Ask for a clean stop; the first reason is kept (`reason`), for the owner to log.
        Never blocks (it runs on the watcher and on transport threads)."""
        with self._lock:
            if self.reason is None:
                self.reason = reason
                self._began = time.monotonic()
        self.stop.set()
        self._wake()

    def close_when_forced(self, closer: Closer) -> None:
        """Run `closer(seconds)` before a forced exit (registration order)."""
        with self._lock:
            self._closers.append(closer)

    def stopping(self) -> None:
        """The loop has ended (stopped, or its duration is over): the stop begins now,
        unless it began already."""
        with self._lock:
            if self._began is None:
                self._began = time.monotonic()
        self._wake()

    def done(self) -> None:
        """The clean stop is over: nothing is forced any more."""
        self._done = True
        self._wake()

    # -- the watcher thread -----------------------------------------------------------

    def _wake(self) -> None:
        with contextlib.suppress(OSError):  # full: the watcher is awake anyway
            self._write.send(bytes([_WAKE]))

    def _timeout(self) -> float | None:
        """Seconds the clean stop has left, or None: no deadline (yet)."""
        with self._lock:
            began = self._began
        if self.deadline_s is None or began is None:
            return None
        return max(began + self.deadline_s - time.monotonic(), 0.0)

    def _watch(self) -> None:
        while not self._done:
            self._read.settimeout(self._timeout())
            try:
                received = self._read.recv(64)
            except TimeoutError:
                if not self._done:
                    self._force_overrun()
                return
            except OSError:
                return
            if not received:
                return
            for number in received:
                if number in STOP_SIGNALS:
                    self._on_signal(signal.Signals(number))

    def _on_signal(self, number: signal.Signals) -> None:
        self._signals += 1
        if self._signals == 1:
            self.request(number.name)
            return
        self._force(128 + number, f"{number.name} again: exiting now, without a clean stop")

    def _force_overrun(self) -> None:
        why = (
            f"the stop ({self.reason or 'the loop ended'}) did not finish within "
            f"{self.deadline_s:.1f} s; exiting now. Where each thread was:"
        )
        self._force(EXIT_STOP_FORCED, why, stacks=True)

    def _force(self, status: int, why: str, stacks: bool = False) -> None:
        """Close the bag, report and exit. The watcher itself never waits on anything
        that may be stuck: closing and reporting log, and what is stuck may be the output
        (a terminal that stopped taking it, a thread holding a log handler's lock), so
        they run on a thread of their own, waited for a bounded time."""
        with self._lock:
            closers = list(self._closers)
        finishing = threading.Thread(
            target=_close_and_report,
            args=(closers, why, stacks),
            name="forced exit",
            daemon=True,
        )
        finishing.start()
        finishing.join(FORCED_CLOSE_S * len(closers) + FORCED_REPORT_S)
        self._exit_process(status)

    # -- life cycle (main thread) -----------------------------------------------------

    @property
    def wakeup_fd(self) -> int:
        """Where the interpreter writes the number of each signal it catches."""
        return self._write.fileno()

    def start(self) -> None:
        self._watcher.start()

    def close(self) -> None:
        self.done()
        self._watcher.join(FORCED_CLOSE_S)
        self._read.close()
        self._write.close()


@contextlib.contextmanager
def stop_on_signals(
    stop: threading.Event,
    deadline_s: float | None = None,
    exit_process: Callable[[int], object] = os._exit,
    *,
    signals: bool = True,
) -> Iterator[StopControl]:
    """SIGINT, SIGTERM and SIGHUP go to a StopControl while inside (see it); the previous
    handlers and wakeup descriptor come back after. Off the main thread, or without
    `signals` (a process that runs one simulation after another handles them itself), no
    signal is handled (Python delivers them to the main thread only), but requests and the
    deadline still work."""
    control = StopControl(stop, deadline_s, exit_process)
    control.start()
    if not signals or threading.current_thread() is not threading.main_thread():
        try:
            yield control
        finally:
            control.close()
        return
    previous_fd = signal.set_wakeup_fd(control.wakeup_fd, warn_on_full_buffer=False)
    # The handlers only make the interpreter write the signal's number to the wakeup fd.
    # A SIGHUP ignored from the start stays so: `nohup egosim run` outlives its terminal.
    numbers = [
        n for n in STOP_SIGNALS if n != signal.SIGHUP or signal.getsignal(n) != signal.SIG_IGN
    ]
    previous = {number: signal.signal(number, _noted) for number in numbers}
    try:
        yield control
    finally:
        for number, handler in previous.items():
            signal.signal(number, handler)
        signal.set_wakeup_fd(previous_fd)
        control.close()


def _close_and_report(closers: list[Closer], why: str, stacks: bool) -> None:
    for closer in closers:
        try:
            closer(FORCED_CLOSE_S)
        except Exception:
            log.exception("closing before the forced exit failed")
    log.error("%s", why)
    if stacks:
        with contextlib.suppress(OSError, ValueError):
            faulthandler.dump_traceback(file=sys.stderr, all_threads=True)
    _flush_output()


def _noted(number: int, frame: object) -> None:
    """The stop watcher reads the signal from the wakeup fd; nothing is left to do here."""


def exit_now(status: int) -> NoReturn:
    """End the process once a command has closed what it opened (the bag, the node):
    output flushed, without the interpreter's teardown. That teardown frees every object
    of the world, the renderer and the view one by one and joins leftover threads; it
    took up to 2 s of a stop on a loaded machine (docs/BENCHMARKS.md, Start and stop)."""
    _flush_output()
    os._exit(status)


def _flush_output() -> None:
    for handler in logging.getLogger().handlers:
        with contextlib.suppress(OSError, ValueError):
            handler.flush()
    for stream in (sys.stdout, sys.stderr):
        with contextlib.suppress(OSError, ValueError):
            stream.flush()
