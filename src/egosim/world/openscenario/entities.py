"""The scenario's entities: what each is (its definition from <Entities>) and where it
is now (its state), in the entity's reference point (a vehicle's rear axle centre, as
OpenSCENARIO has it), SI units, heading counter-clockwise from east."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from enum import Enum
from typing import Protocol

from egosim.world.traffic.objects import ObjectType


class DomainHolder(Protocol):
    """What holds an entity's longitudinal or lateral domain (motion.MotionRun)."""

    follows_path: bool
    overridden: bool

    def release(self, entity: EntityState) -> None: ...


class EntityKind(Enum):
    VEHICLE = "vehicle"
    PEDESTRIAN = "pedestrian"
    MISC_OBJECT = "miscellaneous object"

    @property
    def object_type(self) -> ObjectType:
        return _OBJECT_TYPES[self]


_OBJECT_TYPES = {
    EntityKind.VEHICLE: ObjectType.NPC_VEHICLE,
    EntityKind.PEDESTRIAN: ObjectType.PEDESTRIAN,
    EntityKind.MISC_OBJECT: ObjectType.OBSTACLE,
}


@dataclass(frozen=True)
class VehicleFigures:
    """A <Vehicle>'s axles and mass, as the scenario gives them (reference point: the
    rear axle's centre, so positionX is ahead of it), m, rad and kg."""

    front_axle_x: float
    rear_axle_x: float
    wheel_diameter: float
    track_width: float
    max_steering: float
    mass: float | None = None
    """The Vehicle's mass (1.1+); None when the file gives none."""


@dataclass(frozen=True)
class EntityDefinition:
    """A <ScenarioObject>: its kind, model name and bounding box."""

    name: str
    kind: EntityKind
    model: str
    """The vehicle's, pedestrian's or object's name (what ObjectStatus.name shows)."""
    category: str
    length: float
    width: float
    height: float
    centre: tuple[float, float, float] = (0.0, 0.0, 0.0)
    """The bounding box's centre from the reference point, entity frame, m."""
    max_speed: float = math.inf
    max_acceleration: float = math.inf
    max_deceleration: float = math.inf
    external: bool = False
    """Its controller is external (the user's stack drives it)."""
    properties: tuple[tuple[str, str], ...] = ()
    figures: VehicleFigures | None = None
    """A vehicle's axles and mass (None: no <Axles>, or not a vehicle)."""


@dataclass
class EntityState:
    """Where an entity is and how it moves; kept by the storyboard, applied to the world."""

    definition: EntityDefinition
    x: float = 0.0
    y: float = 0.0
    z: float = 0.0
    heading: float = 0.0
    speed: float = 0.0
    """Along the heading, m/s (negative: reversing)."""
    acceleration: float = 0.0
    lateral_speed: float = 0.0
    """Sideways (left) m/s of a lane change or offset, for the heading it gives."""
    lane: int = -1
    """The egosim lane (index) it follows; -1: none (it moves along its heading)."""
    station: float = 0.0
    offset: float = 0.0
    """Left of the lane's centreline, m."""
    placed: bool = False
    """It has a position (Init placed it, or AddEntityAction added it)."""
    present: bool = True
    """In the world (DeleteEntityAction takes it out)."""
    visible: bool = True
    odometer: float = 0.0
    """Distance travelled since it was placed, m."""
    standstill_s: float = 0.0
    """How long it has stood still, s."""
    is_ego: bool = False
    longitudinal: DomainHolder | None = None
    lateral: DomainHolder | None = None
    route: tuple[int, ...] = ()
    """Lane indices to prefer at forks (AssignRouteAction, AcquirePositionAction)."""
    route_position: int = 0
    end_of_road_s: float = 0.0
    """How long it has stood at the end of a dead-end lane, s."""
    offroad_s: float = 0.0
    teleported: bool = False
    """An action put it somewhere this step (an ego its stack drives goes there too)."""
    collisions: set[str] = field(default_factory=set)
    """Names of the entities (and egosim objects) it touches now."""

    @property
    def name(self) -> str:
        return self.definition.name

    def box_centre(self) -> tuple[float, float]:
        cx, cy, _ = self.definition.centre
        c, s = math.cos(self.heading), math.sin(self.heading)
        return self.x + c * cx - s * cy, self.y + s * cx + c * cy

    def in_world(self) -> bool:
        return self.placed and self.present
