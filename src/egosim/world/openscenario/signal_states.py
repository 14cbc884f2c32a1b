"""Traffic signal states as OpenSCENARIO writes them, as protocol aspects.

A state is either lamp states separated by semicolons, red;yellow;green (each on, off
or flashing: "off;off;on" is green), or a name: red, yellow (amber), green, redYellow,
greenLeft, off.
"""

from __future__ import annotations

from egosim.world.signals.aspects import GREEN, GREEN_LEFT, OFF, RED, YELLOW

_NAMES = {
    "red": RED,
    "stop": RED,
    "yellow": YELLOW,
    "amber": YELLOW,
    "green": GREEN,
    "go": GREEN,
    "redyellow": RED | YELLOW,
    "greenleft": GREEN_LEFT,
    "leftgreen": GREEN_LEFT,
    "off": OFF,
}


def parse_state(text: str) -> int | None:
    """The aspect a state names; None for one egosim cannot show."""
    state = text.strip().lower().replace("_", "").replace(" ", "")
    if ";" in state:
        lamps = [lamp.strip() for lamp in state.split(";")]
        aspect = 0
        for lamp, bit in zip(lamps, (RED, YELLOW, GREEN, GREEN_LEFT), strict=False):
            if lamp in ("on", "flashing", "true", "1"):
                aspect |= bit
        return OFF if aspect == 0 else aspect
    return _NAMES.get(state)


def aspect_matches(aspect: int, wanted: int) -> bool:
    return aspect == wanted
