"""When something published at a rate is due: on a fixed grid of periods from the first
time it goes out, so a loop whose ticks do not divide the period still averages the full
rate, and afresh after a stall, so a late loop does not send a burst to catch up."""

from __future__ import annotations

import math

# Loop times are sums of float steps: a tick meant to land on the grid may fall just short.
_SLACK_S = 1e-9


class RateSchedule:
    """Due times for a rate in Hz; no rate (None or 0) means due at every tick."""

    def __init__(self, rate_hz: float | None) -> None:
        self.period_s = 1.0 / rate_hz if rate_hz else 0.0
        self._next_due = -math.inf

    def is_due(self, now: float) -> bool:
        return now + _SLACK_S >= self._next_due

    def advance(self, now: float) -> None:
        """It went out at `now`: the next is due one period on, on the grid."""
        on_grid = now - self._next_due < self.period_s
        self._next_due = (self._next_due if on_grid else now) + self.period_s

    def take(self, now: float) -> bool:
        """Whether it is due at `now`; if it is, it counts as gone out (is_due, then
        advance, in one call: every row asks at every tick)."""
        next_due = self._next_due
        if now + _SLACK_S < next_due:
            return False
        on_grid = now - next_due < self.period_s
        self._next_due = (next_due if on_grid else now) + self.period_s
        return True
