"""The simulator's clock for message headers, per clock mode."""

from __future__ import annotations

import time
from collections.abc import Callable

from ..world import World
from .options import ClockMode


class HeaderClock:
    """Header stamps (s): wall time in real mode, simulation time in sim and sync modes.

    The wall time is read once per step (`tick`), so every message of one step
    carries the same stamp.
    """

    def __init__(self, mode: ClockMode, world: World, wall: Callable[[], float] = time.time):
        self._mode = mode
        self._world = world
        self._wall = wall
        self._wall_now = wall()

    def tick(self) -> None:
        self._wall_now = self._wall()

    def __call__(self) -> float:
        if self._mode is ClockMode.REAL:
            return self._wall_now
        return self._world.sim_time
