"""What a drive did wrong: infraction kinds and records with their time and place."""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum
from typing import TypedDict


class InfractionKind(str, Enum):
    """The infractions a drive is scored on (their values name them in reports)."""

    COLLISION_PEDESTRIAN = "collision_pedestrian"
    COLLISION_VEHICLE = "collision_vehicle"
    COLLISION_STATIC = "collision_static"
    RED_LIGHT = "red_light"
    STOP_LINE = "stop_line"
    """Crossed a stop line that has no light without having stopped before it."""
    LANE_DEPARTURE = "lane_departure"
    """The body crossed its lane's boundary (one record per excursion)."""
    OFF_ROAD = "off_road"
    """The reference point left every lane (one record per excursion)."""
    WRONG_WAY = "wrong_way"
    """Driving against the direction of the lane it is in (one record per episode)."""
    BLOCKED = "blocked"
    """Stood still longer than the allowed time; ends the drive."""
    TIMEOUT = "timeout"
    """The time limit came before the end of the route."""


COLLISION_KINDS = (
    InfractionKind.COLLISION_PEDESTRIAN,
    InfractionKind.COLLISION_VEHICLE,
    InfractionKind.COLLISION_STATIC,
)


class InfractionRecord(TypedDict):
    """An Infraction as JSON (score.json, results.json)."""

    kind: str
    time_s: float
    x: float
    y: float
    detail: str
    magnitude: float | None


@dataclass(frozen=True)
class Infraction:
    """One infraction: when (simulation time, s) and where (map frame, m) it began."""

    kind: InfractionKind
    time_s: float
    x: float
    y: float
    detail: str = ""
    magnitude: float | None = None
    """Its size where it has one: m beyond the boundary for a lane departure or off-road
    excursion, s for wrong-way driving, m/s for a collision (the ego's speed just before
    the contact)."""

    def as_dict(self) -> InfractionRecord:
        return {
            "kind": self.kind.value,
            "time_s": round(self.time_s, 6),
            "x": round(self.x, 3),
            "y": round(self.y, 3),
            "detail": self.detail,
            "magnitude": None if self.magnitude is None else round(self.magnitude, 6),
        }
