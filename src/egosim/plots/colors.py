"""Colours shared by every egosim figure, so a kind of event looks the same everywhere."""

from __future__ import annotations

import zlib

ROAD = "#d9d9d9"
CENTRE_LINE = "#8c8c8c"
JUNCTION_ROAD = "#e6e6e6"
STOP_LINE = "#222222"
CROSSWALK = "#ffffff"
CROSSWALK_EDGE = "#7f7f7f"
SIDEWALK = "#c9b99a"
LANE_LABEL = "#1f3f7f"
LIGHT_LABEL = "#7f1f1f"
PATH = "#1f77b4"

# Traffic-light aspects in the protocol's bits (GetTrafficLightStatus): red wins, then
# yellow, then the greens; off and unknown lights are grey.
_RED, _YELLOW, _GREEN, _LEFT = 1, 4, 16, 32
LIGHT_RED = "#d62728"
LIGHT_YELLOW = "#ffbf00"
LIGHT_GREEN = "#2ca02c"
LIGHT_UNKNOWN = "#7f7f7f"

_KIND_COLORS = {
    "collision": "#d62728",
    "red_light": "#ff7f0e",
}
_PALETTE = ("#9467bd", "#8c564b", "#e377c2", "#17becf", "#bcbd22", "#7f7f7f", "#1f77b4")


def light_color(aspect: int | None) -> str:
    """The colour of a light showing `aspect` (protocol bits; None: unknown)."""
    if aspect is None or aspect < 0:
        return LIGHT_UNKNOWN
    if aspect & _RED and not aspect & (_GREEN | _LEFT):
        return LIGHT_RED
    if aspect & _YELLOW:
        return LIGHT_YELLOW
    if aspect & (_GREEN | _LEFT):
        return LIGHT_GREEN
    return LIGHT_UNKNOWN


def kind_color(kind: str) -> str:
    """The colour of an event kind: collisions (`collision`, `collision_*`) red, red-light
    violations orange, other kinds a fixed colour derived from their name."""
    for prefix, color in _KIND_COLORS.items():
        if kind == prefix or kind.startswith(prefix + "_"):
            return color
    # crc32, not hash(): the same kind gets the same colour in every process.
    return _PALETTE[zlib.crc32(kind.encode()) % len(_PALETTE)]
