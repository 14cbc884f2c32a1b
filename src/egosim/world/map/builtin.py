"""The maps egosim ships, generated in code."""

from collections.abc import Callable

from egosim.world.map.errors import UnknownMapError
from egosim.world.map.lanes import LaneMap
from egosim.world.map.loop import build_loop
from egosim.world.map.straight import build_straight
from egosim.world.map.town import build_town

_BUILDERS: dict[str, Callable[[], LaneMap]] = {
    "town": build_town,
    "straight": build_straight,
    "loop": build_loop,
}
BUILTIN_MAP_NAMES: tuple[str, ...] = tuple(_BUILDERS)
DEFAULT_MAP_NAME = "town"


def build_builtin_map(name: str) -> LaneMap:
    """A fresh copy of the built-in map `name` (one of BUILTIN_MAP_NAMES)."""
    try:
        builder = _BUILDERS[name]
    except KeyError:
        known = ", ".join(BUILTIN_MAP_NAMES)
        raise UnknownMapError(f"unknown built-in map {name!r}; known maps: {known}") from None
    return builder()
