"""Exceptions raised by the map package."""


class MapError(Exception):
    """Base class for map errors."""


class UnknownMapError(MapError, ValueError):
    """A map name that no built-in map or loader knows."""


class UnknownLaneError(MapError, KeyError):
    """A lane id that is not in the map."""


class MapGeometryError(MapError, ValueError):
    """Map data that violates a geometric invariant (too few points, bad widths...)."""


class MapRecordError(MapError, ValueError):
    """A record of a map file that cannot be read; names the file and the record."""

    def __init__(self, source: str, record: str, reason: str) -> None:
        super().__init__(f"{source}: {record}: {reason}")
        self.source = source
        self.record = record
        self.reason = reason
