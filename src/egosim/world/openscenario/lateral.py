"""Lateral actions while they run: LaneChangeAction, LaneOffsetAction and
LateralDistanceAction (offsets from the lane's centreline, left positive)."""

from __future__ import annotations

import math
from collections.abc import Callable

from egosim.world.openscenario.dynamics import (
    duration_at_peak_second_derivative,
    duration_at_rate,
    progress,
)
from egosim.world.openscenario.entities import EntityState
from egosim.world.openscenario.motion import MotionRun
from egosim.world.openscenario.positions import beside
from egosim.world.openscenario.runtime import Runtime

TargetLane = Callable[[Runtime, EntityState], int]


class LaneChangeRun(MotionRun):
    """The entity moves onto the target lane at once, at the offset it has from that
    lane's centreline, and slides to `target_offset` along the shape over the time or
    distance (or at the lateral rate) the dynamics name; it then follows that lane."""

    lateral = True

    def __init__(
        self,
        target_lane: TargetLane,
        target_offset: float,
        shape: str,
        dimension: str,
        value: float,
    ) -> None:
        super().__init__()
        self.target_lane = target_lane
        self.target_offset = target_offset
        self.shape = shape
        self.dimension = dimension
        self.value = value
        self.start_offset = 0.0
        self.elapsed = 0.0
        self.travelled = 0.0
        self.length = 0.0

    def begin(self, rt: Runtime, entity: EntityState) -> None:
        super().begin(rt, entity)
        target = self.target_lane(rt, entity)
        if target != entity.lane and entity.lane >= 0:
            station = beside(rt, entity.lane, entity.station, target)
            x, y, _, heading = rt.lane_map.poses_at([target], [station])[0]
            entity.offset = -(entity.x - x) * math.sin(heading) + (entity.y - y) * math.cos(heading)
            entity.lane, entity.station = target, station
        self.start_offset = entity.offset
        change = self.target_offset - self.start_offset
        self.length = (
            duration_at_rate(self.shape, change, self.value)
            if self.dimension == "rate"
            else max(self.value, 0.0)
        )
        if self.shape == "step":
            self.length = 0.0

    def offset(self, rt: Runtime, entity: EntityState, ds: float, dt: float) -> float:
        self.elapsed += dt
        self.travelled += abs(ds)
        covered = self.travelled if self.dimension == "distance" else self.elapsed
        if self.length <= 0.0 or covered >= self.length - 1e-9:
            self.done = True
            return self.target_offset
        f = progress(self.shape, covered / self.length)
        return self.start_offset + (self.target_offset - self.start_offset) * f


class LaneOffsetRun(MotionRun):
    """LaneOffsetAction: to the target offset (absolute, or relative to an entity's)
    along the shape, as fast as the maximum lateral acceleration allows; continuous: it
    keeps following a relative target afterwards."""

    lateral = True

    def __init__(
        self,
        target: Callable[[Runtime, EntityState], float],
        shape: str,
        max_lateral_acceleration: float,
        continuous: bool,
    ) -> None:
        super().__init__()
        self.target = target
        self.shape = shape
        self.max_lateral_acceleration = max_lateral_acceleration
        self.continuous = continuous
        self.start_offset = 0.0
        self.elapsed = 0.0
        self.duration = 0.0
        self.goal = 0.0

    def begin(self, rt: Runtime, entity: EntityState) -> None:
        super().begin(rt, entity)
        self.start_offset = entity.offset
        self.goal = self.target(rt, entity)
        change = self.goal - self.start_offset
        self.duration = (
            0.0
            if not math.isfinite(self.max_lateral_acceleration)
            else duration_at_peak_second_derivative(
                self.shape, change, self.max_lateral_acceleration
            )
        )

    def offset(self, rt: Runtime, entity: EntityState, ds: float, dt: float) -> float:
        self.elapsed += dt
        goal = self.target(rt, entity) if self.continuous else self.goal
        if self.duration <= 0.0 or self.elapsed >= self.duration - 1e-9:
            self.done = not self.continuous
            return goal
        f = progress(self.shape, self.elapsed / self.duration)
        return self.start_offset + (goal - self.start_offset) * f


class LateralDistanceRun(MotionRun):
    """LateralDistanceAction: the offset that puts the entity `distance` m beside the
    reference entity (on the side it is on), reached at once or within the lateral
    limits; continuous: kept."""

    lateral = True

    def __init__(
        self,
        reference: str,
        distance: float,
        continuous: bool,
        max_lateral_speed: float,
    ) -> None:
        super().__init__()
        self.reference = reference
        self.distance = distance
        self.continuous = continuous
        self.max_lateral_speed = max_lateral_speed

    def offset(self, rt: Runtime, entity: EntityState, ds: float, dt: float) -> float:
        reference = rt.entity(self.reference)
        heading = entity.heading
        across = -(reference.x - entity.x) * math.sin(heading) + (
            reference.y - entity.y
        ) * math.cos(heading)
        side = -1.0 if across >= 0 else 1.0  # the entity stays on its own side
        wanted = entity.offset + across + side * self.distance
        change = wanted - entity.offset
        if math.isfinite(self.max_lateral_speed):
            step = self.max_lateral_speed * dt
            change = min(max(change, -step), step)
        if abs(wanted - (entity.offset + change)) < 1e-3:
            self.done = not self.continuous
        return entity.offset + change
