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
    """Header stamps, in whole nanoseconds: wall time in real mode, simulation time in
    sim and sync modes, and the world's time while synchronous mode holds time.

    The wall time is read once per tick, when the tick's first stamp is asked for (by then
    the world has stepped), so every message of one tick carries the same stamp, and the
    first row built has nothing between its stamp and its send but its own build: work
    done in the tick before it (other stages, rows due with no subscriber) is not counted
    in its latency. While a client holds time (`hold`), each tick advances the stamp by
    exactly its step from the stamp synchronous mode started at, so 20 ms ticks are
    stamped 20 ms apart whatever the wall clock does. When it lets go (`release`), the
    run's own clock goes on from the last stamp (shifted by a fixed offset from then on),
    so stamps never go back.
    """

    def __init__(
        self, mode: ClockMode, world: World, wall: Callable[[], float] = time.time
    ) -> None:
        self.mode = mode
        self._world = world
        self._wall = wall
        self._offset_ns = 0
        self._held = False
        self._now_ns = self._source_ns()
        self._wall_due = False  # a real-time tick is done and its stamp not yet read

    @property
    def publishes_clock(self) -> bool:
        """Headers carry simulation time, so /clock is published (sim and sync modes)."""
        return self.mode is not ClockMode.REAL

    def _source_ns(self) -> int:
        """The run's own clock (wall or simulation time), with the offset of past holds."""
        seconds = self._wall() if self.mode is ClockMode.REAL else self._world.sim_time
        return round(seconds * 1e9) + self._offset_ns

    def hold(self) -> None:
        """Synchronous mode starts (or changes hands): ticks stamp the world's time."""
        if not self._held:
            self._now_ns = self.now_ns()
            self._held = True

    def release(self) -> None:
        """Synchronous mode stops: the run's clock goes on from the last stamp."""
        if self._held:
            self._held = False
            self._offset_ns += self._now_ns - self._source_ns()

    def tick(self, dt: float) -> None:
        """A tick of `dt` s is done: its stamp (in real time, read when first asked for)."""
        if self._held:
            self._now_ns += round(dt * 1e9)
        elif self.mode is ClockMode.REAL:
            self._wall_due = True

    def now_ns(self) -> int:
        if self._held:
            return self._now_ns
        if self.mode is ClockMode.REAL:
            if self._wall_due:
                self._wall_due = False
                self._now_ns = self._source_ns()
            return self._now_ns
        return self._source_ns()

    def __call__(self) -> float:
        """The stamp, s."""
        return self.now_ns() / 1e9
