"""Colours shared by every egosim figure, so a kind of event looks the same everywhere."""

from __future__ import annotations

import zlib

from egosim.world.signals.aspects import shown_colour

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

LIGHT_COLOURS = {"red": "#d62728", "yellow": "#ffbf00", "green": "#2ca02c"}
LIGHT_UNKNOWN = "#7f7f7f"

_KIND_COLORS = {
    "collision": "#d62728",
    "red_light": "#ff7f0e",
}
_PALETTE = ("#9467bd", "#8c564b", "#e377c2", "#17becf", "#bcbd22", "#7f7f7f", "#1f77b4")


def light_color(aspect: int | None) -> str:
    """The colour of a light showing `aspect` (protocol bits; None: unknown; dark: grey)."""
    shown = None if aspect is None else shown_colour(aspect)
    return LIGHT_UNKNOWN if shown is None else LIGHT_COLOURS[shown]


def kind_color(kind: str) -> str:
    """The colour of an event kind: collisions (`collision`, `collision_*`) red, red-light
    violations orange, other kinds a fixed colour derived from their name."""
    for prefix, color in _KIND_COLORS.items():
        if kind == prefix or kind.startswith(prefix + "_"):
            return color
    # crc32, not hash(): the same kind gets the same colour in every process.
    return _PALETTE[zlib.crc32(kind.encode()) % len(_PALETTE)]
