"""Hands work from ROS threads to the simulation loop's thread.

Topic callbacks and service handlers run on transport threads; the world is
touched only by the loop thread, between steps, so a step never sees a
half-applied command and runs are reproducible.
"""

from __future__ import annotations

import logging
import queue
import threading
from collections.abc import Callable
from concurrent.futures import Future
from typing import TypeVar

from ..ros1 import NodeShutdownError

T = TypeVar("T")
log = logging.getLogger(__name__)


class LoopStoppedError(NodeShutdownError):
    """The simulation loop stopped before it could run the work (a service call that comes
    as the run stops is answered with this error, as one to a node shutting down)."""


class Inbox:
    def __init__(self) -> None:
        # Not queue.SimpleQueue: its get(timeout) can miss its timeout for good when a
        # signal interrupts it near the end (the interpreter's retry then waits with a
        # negative timeout, which means forever), and the loop waits here all the time;
        # a Ctrl-C then stopped nothing until the next message came (tests/app/test_inbox.py).
        self._work: queue.Queue[tuple[Callable[[], object], Future[object] | None]] = queue.Queue()
        self._closed = False
        # A call is queued, or refused, as one step with close(): none can slip in after
        # close() failed the waiting ones and then wait for a loop that is gone.
        self._closing = threading.Lock()

    def post(self, work: Callable[[], object]) -> None:
        """Run `work` on the loop thread at its next drain; do not wait (dropped once closed)."""
        self._work.put((work, None))

    def call(self, work: Callable[[], T], timeout: float | None = 10.0) -> T:
        """Run `work` on the loop thread and return its result (or raise its error).
        LoopStoppedError once the inbox is closed, also while waiting."""
        future: Future[T] = Future()
        with self._closing:
            if self._closed:
                raise LoopStoppedError("the simulation is stopping")
            self._work.put((work, future))  # type: ignore[arg-type]
        return future.result(timeout)

    def drain(self) -> int:
        """Run everything posted so far (loop thread only); the number of items run."""
        count = 0
        while True:
            try:
                work, future = self._work.get_nowait()
            except queue.Empty:
                return count
            count += 1
            self._run(work, future)

    def wait(self, timeout: float) -> bool:
        """Block until work arrives or `timeout` s pass; run the first item. True if one ran."""
        try:
            work, future = self._work.get(timeout=timeout)
        except queue.Empty:
            return False
        self._run(work, future)
        return True

    def close(self) -> None:
        """Refuse new calls and fail the ones still waiting."""
        with self._closing:
            self._closed = True
        while True:
            try:
                _, future = self._work.get_nowait()
            except queue.Empty:
                return
            if future is not None:
                future.set_exception(LoopStoppedError("the simulation is stopping"))

    @staticmethod
    def _run(work: Callable[[], object], future: Future[object] | None) -> None:
        if future is None:
            try:
                work()
            except Exception:
                # A bad message must not stop the simulation; its handler's error is logged.
                log.exception("error while applying a received message")
            return
        try:
            future.set_result(work())
        except Exception as exc:  # handed to the waiting thread, which re-raises it
            future.set_exception(exc)
