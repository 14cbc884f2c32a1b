"""Threads for a server's connections: each connection is served in a thread of its own,
as by a new thread per connection, but a thread whose connection has ended waits a moment
for the next one instead of ending.

rospy's ServiceProxy opens a connection for every call (and every XML-RPC client one
for every request): a thread started and ended per call costs the server as much CPU as
the request itself, and the wait for the new thread to start. A thread kept waiting
takes the next connection at the cost of a wake-up.
"""

from __future__ import annotations

import logging
import threading
from collections.abc import Callable

log = logging.getLogger(__name__)

IDLE_S = 1.0
"""How long a thread whose connection ended waits for another before it ends."""

Job = Callable[[], None]


class HandlerThreads:
    def __init__(self, idle_s: float = IDLE_S) -> None:
        self._idle_s = idle_s
        self._lock = threading.Lock()
        self._waiting: list[_Waiting] = []
        self._closed = False

    @property
    def waiting(self) -> int:
        """Threads waiting for their next job now."""
        with self._lock:
            return len(self._waiting)

    def run(self, job: Job, name: str) -> None:
        """Run `job` in a thread of its own named `name`: a waiting one, else a new one
        (also once closed: what is still running ends as a thread per job would)."""
        with self._lock:
            waiting = self._waiting.pop() if self._waiting else None
        if waiting is not None:
            waiting.hand(job, name)
            return
        threading.Thread(target=self._serve, args=(job,), name=name, daemon=True).start()

    def close(self) -> None:
        """No thread waits for another connection from now on: the waiting ones end."""
        with self._lock:
            self._closed = True
            waiting, self._waiting = self._waiting, []
        for thread in waiting:
            thread.hand(None, "")

    def _serve(self, job: Job | None) -> None:
        while job is not None:
            try:
                job()
            except Exception:  # a handler's bug must not end the threads of the others
                log.exception("connection handler failed")
            job = self._next_job()

    def _next_job(self) -> Job | None:
        waiting = _Waiting()
        with self._lock:
            if self._closed:
                return None
            self._waiting.append(waiting)
        job = waiting.take(self._idle_s)
        if job is None:
            with self._lock:
                if waiting in self._waiting:
                    self._waiting.remove(waiting)
                    return None
            # Handed a job (or told to end) just as it stopped waiting: that decides.
            job = waiting.take(None)
        return job


class _Waiting:
    """A thread waiting for its next job."""

    def __init__(self) -> None:
        self._handed = threading.Event()
        self._job: Job | None = None
        self._name = ""

    def hand(self, job: Job | None, name: str) -> None:
        """The thread's next job (None: end)."""
        self._job, self._name = job, name
        self._handed.set()

    def take(self, timeout_s: float | None) -> Job | None:
        """The job handed within `timeout_s` (None: wait until one is), else None."""
        if not self._handed.wait(timeout_s):
            return None
        if self._job is not None:
            threading.current_thread().name = self._name
        return self._job
