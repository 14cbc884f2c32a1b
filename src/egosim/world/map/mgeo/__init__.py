"""MGeo (MORAI SIM's map format: a folder of JSON files) -> LaneMap, from parsed JSON.

Public API:
    build_mgeo_map(name, files, notes)  {file name: parsed JSON} -> LaneMap
    read_georeference(global_info)      global_info.json -> GeoReference
    light_type_of(sub_type)             MGeo light sub-type -> protocol trafficLightType
    mgeo_files(lane_map)                LaneMap -> {file name: JSON data} (writing MGeo)
    MGEO_FILES, REQUIRED_FILES          the file names read
"""

from egosim.world.map.mgeo.build import (
    MGEO_FILES,
    REQUIRED_FILES,
    build_mgeo_map,
    read_georeference,
)
from egosim.world.map.mgeo.light_types import light_type_of
from egosim.world.map.mgeo.write import mgeo_files

__all__ = [
    "MGEO_FILES",
    "REQUIRED_FILES",
    "build_mgeo_map",
    "light_type_of",
    "mgeo_files",
    "read_georeference",
]
