"""Exceptions raised by the map package."""


class MapError(Exception):
    """Base class for map errors."""


class UnknownMapError(MapError, ValueError):
    """A map name that no built-in map or loader knows."""


class UnknownLaneError(MapError, KeyError):
    """A lane id that is not in the map."""


class MapGeometryError(MapError, ValueError):
    """Map data that violates a geometric invariant (too few points, bad widths...)."""
