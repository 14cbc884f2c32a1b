"""Transmission selector positions.

The values are the ones of EventInfo.gear so the bridge maps them one to one.
"""

from __future__ import annotations

from enum import IntEnum


class Gear(IntEnum):
    PARKING = 1
    REVERSE = 2
    NEUTRAL = 3
    DRIVE = 4

    @property
    def drive_direction(self) -> int:
        """+1 if the powertrain pushes forwards, -1 backwards, 0 if it is disconnected."""
        return _DRIVE_DIRECTIONS.get(self, 0)


_DRIVE_DIRECTIONS = {Gear.DRIVE: 1, Gear.REVERSE: -1}
