"""Traffic lights and the fixed-time controllers of signalised intersections.

Public API:
    TrafficSignals, IntersectionProgram, LightState   the map's lights, programs, overrides
    IntersectionController, IntersectionStatus        one intersection's program runner
    Phase, PhaseTiming, build_program                 phase programs
    governing_light_id, nearest_light_id              the head a vehicle looks at
    LaneSignals, combined_aspect                      a stop line's heads read together
    RED, YELLOW, GREEN, GREEN_LEFT, OFF, LightType, can_show,
        LEFT_ARROW_TYPES, has_left_arrow   aspects and head types
    SignalError and subclasses
"""

from egosim.world.map.light_type import LightType
from egosim.world.signals.aspects import (
    GREEN,
    GREEN_LEFT,
    LEFT_ARROW_TYPES,
    OFF,
    RED,
    YELLOW,
    can_show,
    has_left_arrow,
)
from egosim.world.signals.controller import IntersectionController, IntersectionStatus
from egosim.world.signals.errors import (
    SignalError,
    UnknownIntersectionError,
    UnknownLightError,
    UnknownPhaseError,
    UnsupportedAspectError,
)
from egosim.world.signals.governing import governing_light_id, nearest_light_id
from egosim.world.signals.lane_signals import LaneSignals, combined_aspect
from egosim.world.signals.phases import Phase, PhaseTiming, build_program
from egosim.world.signals.system import IntersectionProgram, LightState, TrafficSignals

__all__ = [
    "GREEN",
    "GREEN_LEFT",
    "LEFT_ARROW_TYPES",
    "OFF",
    "RED",
    "YELLOW",
    "IntersectionController",
    "IntersectionProgram",
    "IntersectionStatus",
    "LaneSignals",
    "LightState",
    "LightType",
    "Phase",
    "PhaseTiming",
    "SignalError",
    "TrafficSignals",
    "UnknownIntersectionError",
    "UnknownLightError",
    "UnknownPhaseError",
    "UnsupportedAspectError",
    "build_program",
    "can_show",
    "combined_aspect",
    "governing_light_id",
    "has_left_arrow",
    "nearest_light_id",
]
