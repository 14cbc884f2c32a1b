"""Rates of angles the world does not report, from two readings in simulation time."""

from __future__ import annotations

import math


class AngleRates:
    """d(angle)/dt of named angles between two readings of simulation time (rad/s)."""

    def __init__(self) -> None:
        self._last: dict[object, tuple[float, float]] = {}

    def rate(self, key: object, angle: float, now: float) -> float:
        previous = self._last.get(key)
        self._last[key] = (now, angle)
        if previous is None or now <= previous[0]:
            return 0.0
        change = math.remainder(angle - previous[1], math.tau)
        return change / (now - previous[0])
