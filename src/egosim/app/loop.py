"""The simulation loop: steps the world at a fixed dt, paced against the wall clock.

Everything that touches the world runs here, on one thread: steps, and the
received messages and service calls handed over through the inbox between
steps.
"""

from __future__ import annotations

import logging
import threading
import time
from collections.abc import Callable

from ..logthrottle import LogThrottle
from .inbox import Inbox

log = logging.getLogger(__name__)
throttle = LogThrottle(log)

#: Falling this far behind the wall clock (s) resets the pace instead of racing to catch up.
MAX_LAG_S = 0.25
#: How often an idle loop (sync mode, paused) wakes to check for a stop request (s).
IDLE_POLL_S = 0.05


class SimulationLoop:
    """Calls `step` every `dt` of simulated time at `rtf` times real time (0: flat out),
    except while `held` says a client owns time (sync mode), when it only runs the work
    handed over (the client's calls step the world). It ends when stopped, after
    `max_steps`, or once `done` says the run is over (a scenario's end)."""

    def __init__(
        self,
        step: Callable[[], object],
        inbox: Inbox,
        dt: float,
        rtf: float,
        stop: threading.Event,
        max_steps: int | None = None,
        monotonic: Callable[[], float] = time.monotonic,
        held: Callable[[], bool] = lambda: False,
        done: Callable[[], bool] | None = None,
    ) -> None:
        self._step = step
        self._held = held
        self._done = done
        self._inbox = inbox
        self._dt = dt
        self._rtf = rtf
        self._stop = stop
        self._max_steps = max_steps
        self._monotonic = monotonic
        self.steps = 0
        self.lag_resets = 0

    def run(self) -> None:
        """Step until stopped or `max_steps` is reached."""
        next_wall = self._monotonic()
        while not self._stop.is_set():
            if self._max_steps is not None and self.steps >= self._max_steps:
                return
            if self._done is not None and self._done():
                return
            if self._held():
                self._inbox.wait(IDLE_POLL_S)
                # Time held by a client is not time the loop fell behind.
                next_wall = self._monotonic()
                continue
            self._inbox.drain()
            self._step()
            self.steps += 1
            if self._rtf > 0:
                next_wall = self._pace(next_wall + self._dt / self._rtf)

    def _pace(self, target: float) -> float:
        """Serve the inbox until the wall clock reaches `target`; the next target base."""
        while (remaining := target - self._monotonic()) > 0:
            if self._stop.is_set():
                return target
            self._inbox.wait(remaining)
        if -remaining > MAX_LAG_S:
            self.lag_resets += 1
            throttle.log(
                logging.WARNING,
                "lag",
                "simulation fell %.2f s behind real time; skipping ahead (%d times so far)",
                -remaining,
                self.lag_resets,
            )
            return self._monotonic()
        return target
