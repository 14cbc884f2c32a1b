"""OpenDRIVE (.xodr) -> LaneMap, from the document's text.

Public API:
    build_opendrive_map(name, xml_text, notes)   OpenDRIVE XML -> LaneMap
    light_type_of(type, subtype)                 signal type -> protocol trafficLightType
    evaluate, Pose2, Line, Arc, Spiral, ParamPoly3   reference-line geometry
"""

from egosim.world.map.opendrive.build import build_opendrive_map
from egosim.world.map.opendrive.geometry import Arc, Line, ParamPoly3, Pose2, Spiral, evaluate
from egosim.world.map.opendrive.light_types import light_type_of

__all__ = [
    "Arc",
    "Line",
    "ParamPoly3",
    "Pose2",
    "Spiral",
    "build_opendrive_map",
    "evaluate",
    "light_type_of",
]
