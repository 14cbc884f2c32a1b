"""The simulator's clock modes and the clock that stamps message headers."""

from __future__ import annotations

import time
from collections.abc import Callable
from enum import Enum

from ..world import World


class ClockMode(Enum):
    REAL = "real"  # headers carry wall time; the world advances in real time
    SIM = "sim"  # /clock published, /use_sim_time set, run at --rtf (0: as fast as possible)
    SYNC = "sync"  # as SIM, but starting in MORAI's synchronous mode: the client steps the world


class HeaderClock:
    """Header stamps (s): wall time in real mode, simulation time in sim and sync modes.

    The wall time is read once per tick (`tick`), so every message of one tick
    carries the same stamp.
    """

    def __init__(
        self, mode: ClockMode, world: World, wall: Callable[[], float] = time.time
    ) -> None:
        self.mode = mode
        self._world = world
        self._wall = wall
        self._wall_now = wall()

    @property
    def publishes_clock(self) -> bool:
        """Headers carry simulation time, so /clock is published (sim and sync modes)."""
        return self.mode is not ClockMode.REAL

    def tick(self) -> None:
        self._wall_now = self._wall()

    def __call__(self) -> float:
        if self.mode is ClockMode.REAL:
            return self._wall_now
        return self._world.sim_time
