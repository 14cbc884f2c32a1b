"""Light aspects and head types, in the protocol's own codes (GetTrafficLightStatus).

An aspect is an int of lamp bits combined with bitwise OR (RED | GREEN_LEFT is a red
light with a lit left arrow); OFF (-1) means no lamp is lit. A head's type (the map's
light_type) fixes which lamps it has, and so which aspects it can show.
"""

from __future__ import annotations

from egosim.world.map.light_type import LightType

RED = 1
YELLOW = 4
GREEN = 16
GREEN_LEFT = 32
OFF = -1

LAMPS_BY_TYPE: dict[int, int] = {
    LightType.RYG: RED | YELLOW | GREEN,
    LightType.RYG_LEFT: RED | YELLOW | GREEN_LEFT,
    LightType.RYG_LEFT_GREEN: RED | YELLOW | GREEN | GREEN_LEFT,
    LightType.FLASHING_YELLOW: YELLOW,
}


LEFT_ARROW_TYPES = tuple(t for t in LightType if t.has_left_arrow)
"""Head types with a left-arrow lamp."""


def has_left_arrow(light_type: int) -> bool:
    return light_type in LEFT_ARROW_TYPES


def has_green(light_type: int) -> bool:
    return bool(LAMPS_BY_TYPE.get(light_type, 0) & GREEN)


def go_lamps(light_type: int) -> int:
    """The aspect letting every movement under a head go: its green and left arrow."""
    return LAMPS_BY_TYPE.get(light_type, 0) & (GREEN | GREEN_LEFT)


def can_show(light_type: int, aspect: int) -> bool:
    """True if a head of `light_type` has every lamp `aspect` lights (OFF always works)."""
    if aspect == OFF:
        return True
    lamps = LAMPS_BY_TYPE.get(light_type)
    return lamps is not None and aspect > 0 and aspect & ~lamps == 0
