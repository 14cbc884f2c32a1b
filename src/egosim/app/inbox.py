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
from typing import TypeVar, cast

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
        self._work: queue.Queue[tuple[Callable[[], object], _Reply | None]] = queue.Queue()
        self._closed = False
        # A call is queued, or refused, as one step with close(): none can slip in after
        # close() failed the waiting ones and then wait for a loop that is gone.
        self._closing = threading.Lock()

    def post(self, work: Callable[[], object]) -> None:
        """Run `work` on the loop thread at its next drain; do not wait (dropped once closed)."""
        self._work.put((work, None))

    def call(self, work: Callable[[], T], timeout: float | None = 10.0) -> T:
        """Run `work` on the loop thread and return its result (or raise its error).
        LoopStoppedError once the inbox is closed, also while waiting; TimeoutError when
        the loop has not run it within `timeout` s."""
        reply = _Reply()
        with self._closing:
            if self._closed:
                raise LoopStoppedError("the simulation is stopping")
            self._work.put((work, reply))
        if not reply.wait(timeout):
            raise TimeoutError(f"the simulation loop did not run the call within {timeout} s")
        if reply.error is not None:
            raise reply.error
        return cast(T, reply.result)

    def drain(self) -> int:
        """Run everything posted so far (loop thread only); the number of items run."""
        count = 0
        while True:
            try:
                work, reply = self._work.get_nowait()
            except queue.Empty:
                return count
            count += 1
            self._run(work, reply)

    def wait(self, timeout: float) -> bool:
        """Block until work arrives or `timeout` s pass; run the first item. True if one ran."""
        try:
            work, reply = self._work.get(timeout=timeout)
        except queue.Empty:
            return False
        self._run(work, reply)
        return True

    def close(self) -> None:
        """Refuse new calls and fail the ones still waiting."""
        with self._closing:
            self._closed = True
        while True:
            try:
                _, reply = self._work.get_nowait()
            except queue.Empty:
                return
            if reply is not None:
                reply.settle(error=LoopStoppedError("the simulation is stopping"))

    @staticmethod
    def _run(work: Callable[[], object], reply: _Reply | None) -> None:
        if reply is None:
            try:
                work()
            except Exception:
                # A bad message must not stop the simulation; its handler's error is logged.
                log.exception("error while applying a received message")
            return
        try:
            result = work()
        except Exception as exc:  # handed to the waiting thread, which re-raises it
            reply.settle(error=exc)
        else:
            reply.settle(result=result)


class _Reply:
    """The outcome of one call, handed back to the waiting thread.

    A bare lock rather than a concurrent.futures.Future: the round trip is the same or
    a little faster, and a call that times out raises the builtin TimeoutError its
    callers catch (on Python 3.10 a Future raises concurrent.futures.TimeoutError, a
    different class)."""

    __slots__ = ("_pending", "error", "result")

    def __init__(self) -> None:
        self.result: object = None
        self.error: Exception | None = None
        self._pending = threading.Lock()
        self._pending.acquire()

    def settle(self, result: object = None, error: Exception | None = None) -> None:
        """The call's result, or the error to raise in the waiting thread (loop thread)."""
        self.result, self.error = result, error
        self._pending.release()

    def wait(self, timeout: float | None) -> bool:
        """True once settled; False after `timeout` s (None: no limit)."""
        return self._pending.acquire(timeout=-1 if timeout is None else timeout)
