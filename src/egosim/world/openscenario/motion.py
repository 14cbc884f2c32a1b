"""The default controller: how the scenario moves an entity through one step.

Longitudinally the entity holds its speed unless a longitudinal action sets it; it moves
the trapezoid of the step's start and end speeds. Laterally it follows the lane it is on
(over lane ends onto its route's lane, else the straightest successor), at the offset a
lateral action gives it, its heading turned with the sideways motion; an entity on a
trajectory follows the trajectory; one on no lane goes straight along its heading.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from functools import partial
from typing import TypeVar

from egosim.world.openscenario.entities import EntityState
from egosim.world.openscenario.lane_paths import advance
from egosim.world.openscenario.runtime import Runtime, UnknownEntityError

STANDSTILL_MPS = 1e-3
MIN_HEADING_SPEED_MPS = 0.1
OFFROAD_MARGIN_M = 0.0


class MotionRun:
    """An action that moves an entity in one or both domains while it runs."""

    longitudinal = False
    lateral = False
    follows_path = False
    """Lateral motion along a path of its own (a trajectory), not along the lane."""

    def __init__(self) -> None:
        self.done = False
        """It has reached what it was for (its event may complete)."""
        self.overridden = False

    def speed(self, rt: Runtime, entity: EntityState, dt: float) -> float:
        """The entity's speed at the end of this step, m/s."""
        return entity.speed

    def offset(self, rt: Runtime, entity: EntityState, ds: float, dt: float) -> float:
        """The entity's offset from its lane's centreline at the end of this step, m."""
        return entity.offset

    def follow(self, rt: Runtime, entity: EntityState, ds: float, dt: float) -> None:
        """Place the entity `ds` further along its path."""

    def begin(self, rt: Runtime, entity: EntityState) -> None:
        """Take over the entity's domains, ending the actions that held them."""
        if self.longitudinal:
            if entity.longitudinal is not None and entity.longitudinal is not self:
                entity.longitudinal.overridden = True
            entity.longitudinal = self
        if self.lateral:
            if entity.lateral is not None and entity.lateral is not self:
                entity.lateral.overridden = True
            entity.lateral = self

    def release(self, entity: EntityState) -> None:
        """Give the entity's domains back (the action ended or was stopped)."""
        if entity.longitudinal is self:
            entity.longitudinal = None
        if entity.lateral is self:
            entity.lateral = None


def move_all(rt: Runtime, entities: list[EntityState], dt: float) -> None:
    """Advance scenario-driven entities by dt s; those following lanes are placed on
    them together (one lane-map lookup for all). Every speed is worked out before anyone
    moves, so each action reads the others as they were at the step's start (a
    synchronised entity does not see its master a step ahead)."""
    speeds = [_guarded(rt, entity, _speed_after, dt, entity.speed) for entity in entities]
    on_lanes = []
    for entity, v1 in zip(entities, speeds, strict=True):
        if _guarded(rt, entity, partial(move, v1=v1), dt, False):
            on_lanes.append(entity)
    if not on_lanes:
        return
    poses = rt.lane_map.poses_at([e.lane for e in on_lanes], [e.station for e in on_lanes])
    for entity, (x, y, z, heading) in zip(on_lanes, poses.tolist(), strict=True):
        x0, y0 = entity.x, entity.y
        entity.x = x - entity.offset * math.sin(heading)
        entity.y = y + entity.offset * math.cos(heading)
        entity.z = z
        forward = max(abs(entity.speed), MIN_HEADING_SPEED_MPS)
        entity.heading = heading + math.atan2(entity.lateral_speed, forward)
        entity.odometer += math.hypot(entity.x - x0, entity.y - y0)


T = TypeVar("T")


def _guarded(
    rt: Runtime,
    entity: EntityState,
    work: Callable[[Runtime, EntityState, float], T],
    dt: float,
    otherwise: T,
) -> T:
    """`work` for the entity; `otherwise` (said once) when its action names an entity
    the running scenario does not have."""
    try:
        return work(rt, entity, dt)
    except UnknownEntityError as error:
        rt.note_once(f"{entity.name!r} holds its motion: its action refers to {error}")
        return otherwise


def _speed_after(rt: Runtime, entity: EntityState, dt: float) -> float:
    """The speed its longitudinal action gives it at the end of this step, within its
    top speed."""
    longitudinal = entity.longitudinal
    v1 = longitudinal.speed(rt, entity, dt) if isinstance(longitudinal, MotionRun) else entity.speed
    top = entity.definition.max_speed
    return min(max(v1, -top), top)


def move(rt: Runtime, entity: EntityState, dt: float, v1: float) -> bool:
    """Advance a scenario-driven entity by dt s to speed v1 at the step's end; True when
    it moved along its lane and still needs its pose from there (move_all gives it)."""
    v0 = entity.speed
    ds = 0.5 * (v0 + v1) * dt
    entity.acceleration = (v1 - v0) / dt
    entity.speed = v1
    entity.standstill_s = entity.standstill_s + dt if abs(v1) < STANDSTILL_MPS else 0.0
    x0, y0 = entity.x, entity.y
    lateral = entity.lateral
    if isinstance(lateral, MotionRun) and lateral.follows_path:
        lateral.follow(rt, entity, ds, dt)
    elif entity.lane >= 0:
        _along_lane(rt, entity, ds, dt)
        return True
    else:
        entity.x += ds * math.cos(entity.heading)
        entity.y += ds * math.sin(entity.heading)
        entity.lateral_speed = 0.0
    entity.odometer += math.hypot(entity.x - x0, entity.y - y0)
    return False


def _along_lane(rt: Runtime, entity: EntityState, ds: float, dt: float) -> None:
    """The entity's lane, station and offset after moving ds (its pose: move_all)."""
    lane, station, entity.route_position, at_end = advance(
        rt.lane_map, entity.lane, entity.station, ds, entity.route, entity.route_position
    )
    entity.lane, entity.station = lane, station
    old_offset = entity.offset
    if isinstance(entity.lateral, MotionRun):
        entity.offset = entity.lateral.offset(rt, entity, ds, dt)
    entity.lateral_speed = (entity.offset - old_offset) / dt
    if at_end:
        entity.speed = 0.0 if ds != 0.0 else entity.speed
    entity.end_of_road_s = entity.end_of_road_s + dt if at_end else 0.0
