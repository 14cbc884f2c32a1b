"""Traffic-light head types: the protocol's trafficLightType codes (GetTrafficLightStatus),
which the map's lights carry and which fix the lamps a head has (world/signals/aspects.py)."""

from __future__ import annotations

from enum import IntEnum


class LightType(IntEnum):
    RYG = 0
    """Red / yellow / green."""
    RYG_LEFT = 1
    """Red / yellow / left arrow: a head over left-turn lanes, with no round green."""
    RYG_LEFT_GREEN = 2
    """Red / yellow / left arrow / green."""
    FLASHING_YELLOW = 100
    """Yellow / yellow / yellow: flashes yellow, stops nobody."""

    @property
    def has_left_arrow(self) -> bool:
        return self in (LightType.RYG_LEFT, LightType.RYG_LEFT_GREEN)
