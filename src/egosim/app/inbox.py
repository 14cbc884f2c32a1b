"""Hands work from ROS threads to the simulation loop's thread.

Topic callbacks and service handlers run on transport threads; the world is
touched only by the loop thread, between steps, so a step never sees a
half-applied command and runs are reproducible.
"""

from __future__ import annotations

import logging
import queue
from collections.abc import Callable
from concurrent.futures import Future
from typing import TypeVar

T = TypeVar("T")
log = logging.getLogger(__name__)


class LoopStoppedError(RuntimeError):
    """The simulation loop stopped before it could run the work."""


class Inbox:
    def __init__(self) -> None:
        self._work: queue.SimpleQueue[tuple[Callable[[], object], Future[object] | None]] = (
            queue.SimpleQueue()
        )
        self._closed = False

    def post(self, work: Callable[[], object]) -> None:
        """Run `work` on the loop thread at its next drain; do not wait."""
        self._work.put((work, None))

    def call(self, work: Callable[[], T], timeout: float | None = 10.0) -> T:
        """Run `work` on the loop thread and return its result (or raise its error)."""
        if self._closed:
            raise LoopStoppedError("the simulation is stopping")
        future: Future[T] = Future()
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
