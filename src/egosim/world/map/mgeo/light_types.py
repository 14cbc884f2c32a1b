"""MGeo traffic-light sub-types (the head's lamps) -> the protocol's trafficLightType codes.

An MGeo light lists its lamps in `sub_type`, e.g. ["red", "yellow", "left", "straight"]
(a string such as "red_yellow_straight" is split on "_", ",", "/", "-" and spaces):

| lamps                                   | trafficLightType                      |
|-----------------------------------------|---------------------------------------|
| red, yellow, green (straight)           | 0  R/Y/G                              |
| red, yellow, left arrow (no round green) | 1  R/Y/left arrow                     |
| red, yellow, left arrow, green          | 2  R/Y/left arrow/G                   |
| yellow only                             | 100 Y/Y/Y (flashing yellow)          |

Right-turn and U-turn arrows are not modelled; a head whose lamps match none of the rows
is read as R/Y/G and reported.
"""

from __future__ import annotations

import re

from egosim.world.map.light_type import LightType

_LAMP_NAMES = {
    "red": "red",
    "r": "red",
    "yellow": "yellow",
    "y": "yellow",
    "green": "green",
    "g": "green",
    "straight": "green",
    "left": "left",
    "leftarrow": "left",
    "left_arrow": "left",
    "l": "left",
    "right": "other",
    "rightarrow": "other",
    "uturn": "other",
    "u_turn": "other",
}
_SEPARATORS = re.compile(r"[\s,/_\-]+")


def lamps_of(sub_type: object) -> list[str]:
    """Lamp words of a sub_type: a list of names or one string of names."""
    if isinstance(sub_type, list):
        words = [str(word).strip().lower() for word in sub_type]
    else:
        words = [w for w in _SEPARATORS.split(str(sub_type or "").lower()) if w]
    return [_LAMP_NAMES.get(word.replace(" ", ""), "unknown") for word in words]


def light_type_of(sub_type: object) -> LightType | None:
    """The trafficLightType of a head, None when the sub_type names no known head."""
    lamps = set(lamps_of(sub_type))
    if "unknown" in lamps:
        return None
    has_red, has_green, has_left = "red" in lamps, "green" in lamps, "left" in lamps
    if lamps - {"other"} == {"yellow"}:
        return LightType.FLASHING_YELLOW
    if not has_red or "yellow" not in lamps:
        return None
    if has_left:
        return LightType.RYG_LEFT_GREEN if has_green else LightType.RYG_LEFT
    return LightType.RYG if has_green else None
