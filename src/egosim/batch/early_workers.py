"""Simulator workers started as `egosim batch` begins, before the driver imports what it
runs on and loads the suite: a worker's own start (a new Python importing egosim, numpy,
numba and rosbags: about 0.9 s of CPU) then runs beside the driver's (about 1.8 s, mostly
imports) instead of after it. The local pool's slots take them (pool.run_local); a slot
left without one starts its own with its first case, as a Ray actor does, and those no
slot takes (fewer cases than workers, a suite that did not load, a batch stopped before
its cases) end at once.
"""

from __future__ import annotations

import os
from types import TracebackType

from egosim.batch.warm_simulator import WarmSimulator


def default_workers() -> int:
    """The local pool's slots unless told: the cores this process may run on."""
    return max(len(os.sched_getaffinity(0)), 1)


class EarlyWorkers:
    """Workers for a local pool of `slots` slots, started on entering: one per slot, at
    most one per core (more would only take CPU from the driver's start and from each
    other; the rest start with their slot's first case). Whatever no slot took ends on
    leaving."""

    def __init__(self, slots: int) -> None:
        self._count = min(slots, default_workers())
        self._idle: list[WarmSimulator] = []

    def __enter__(self) -> EarlyWorkers:
        try:
            for _ in range(self._count):
                simulator = WarmSimulator()
                self._idle.append(simulator)
                simulator.start()
        except BaseException:
            self.close()
            raise
        return self

    def __exit__(
        self,
        kind: type[BaseException] | None,
        error: BaseException | None,
        traceback: TracebackType | None,
    ) -> None:
        self.close()

    def take(self) -> WarmSimulator:
        """A started worker for a slot, else one its first case starts."""
        return self._idle.pop() if self._idle else WarmSimulator()

    def close(self) -> None:
        """End every worker no slot took, at once: none has run a case."""
        while self._idle:
            self._idle.pop().discard()
