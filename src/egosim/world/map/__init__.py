"""Lane-graph maps: geometry, queries, georeference and the built-in maps."""

from egosim.world.map.builtin import BUILTIN_MAP_NAMES, DEFAULT_MAP_NAME, build_builtin_map
from egosim.world.map.errors import (
    MapError,
    MapGeometryError,
    MapRecordError,
    UnknownLaneError,
    UnknownMapError,
)
from egosim.world.map.georef import GeoReference
from egosim.world.map.lanes import (
    Crosswalk,
    IntersectionSite,
    Lane,
    LaneMap,
    Sidewalk,
    TrafficLightSite,
)
from egosim.world.map.projection import LaneProjection, LaneProjections, ProjectionMemory

__all__ = [
    "BUILTIN_MAP_NAMES",
    "DEFAULT_MAP_NAME",
    "Crosswalk",
    "GeoReference",
    "IntersectionSite",
    "Lane",
    "LaneMap",
    "LaneProjection",
    "LaneProjections",
    "MapError",
    "MapGeometryError",
    "MapRecordError",
    "ProjectionMemory",
    "Sidewalk",
    "TrafficLightSite",
    "UnknownLaneError",
    "UnknownMapError",
    "build_builtin_map",
]
