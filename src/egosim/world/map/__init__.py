"""Lane-graph maps: geometry, queries, georeference and the built-in maps."""

from egosim.world.map.errors import MapError, MapGeometryError, UnknownLaneError, UnknownMapError
from egosim.world.map.georef import GeoReference

__all__ = [
    "GeoReference",
    "MapError",
    "MapGeometryError",
    "UnknownLaneError",
    "UnknownMapError",
]
