"""FollowTrajectoryAction while it runs: the entity moves along the trajectory's path,
at its own speed (TimeReference None) or as the path's times say (Timing)."""

from __future__ import annotations

import math
from dataclasses import dataclass

from egosim.world.openscenario.entities import EntityState
from egosim.world.openscenario.geometry_path import SampledPath
from egosim.world.openscenario.motion import MotionRun
from egosim.world.openscenario.positions import PathSource, Placement, attach
from egosim.world.openscenario.runtime import Runtime


@dataclass(frozen=True)
class Timing:
    """<Timing>: path time T is simulation time T·scale + offset (absolute) or that after
    the action starts (relative)."""

    relative: bool
    scale: float = 1.0
    offset: float = 0.0


class TrajectoryRun(MotionRun):
    """The entity is put on the trajectory (initialDistanceOffset along it) and moves
    along it until its end, then follows the lane it stands on."""

    lateral = True
    follows_path = True

    def __init__(
        self, trajectory: PathSource, timing: Timing | None, initial_distance: float | None
    ) -> None:
        super().__init__()
        self.trajectory = trajectory
        self.timing = timing
        self.longitudinal = timing is not None
        self.initial_distance = initial_distance
        self.path: SampledPath | None = None
        self.s = 0.0
        self.due: float | None = None
        self.started_at = 0.0

    def begin(self, rt: Runtime, entity: EntityState) -> None:
        super().begin(rt, entity)
        path = self.path = self.trajectory.path(rt, entity)
        self.started_at = rt.time
        # The entity starts on the trajectory, initialDistanceOffset along it.
        self.s = self.initial_distance or 0.0
        if self.timing is not None and path.timed:
            self.s = path.station_at_time(self._path_time(rt.time))
        self._put(entity)
        entity.placed = True

    def _path_time(self, time: float) -> float:
        timing = self.timing
        assert timing is not None
        base = self.started_at if timing.relative else 0.0
        return (time - base - timing.offset) / (timing.scale or 1.0)

    def speed(self, rt: Runtime, entity: EntityState, dt: float) -> float:
        path = self.path
        if self.timing is None or path is None or not path.timed:
            return entity.speed
        self.due = path.station_at_time(self._path_time(rt.time + dt))
        return (self.due - self.s) / dt  # the step's mean speed

    def follow(self, rt: Runtime, entity: EntityState, ds: float, dt: float) -> None:
        path = self.path
        if path is None:
            return
        # A timed path is where its times say; an untimed one where the speed took it.
        self.s = self.due if self.due is not None else self.s + ds
        self.due = None
        self._put(entity)
        entity.lateral_speed = 0.0
        if self.s >= path.length - 1e-9 or self.s < 0.0:
            self.done = True
            self.release(entity)
            lane = attach(rt, Placement(entity.x, entity.y, entity.z, entity.heading))
            if lane is not None:
                entity.lane, entity.station, entity.offset = (
                    lane.lane_index,
                    lane.station,
                    lane.offset,
                )

    def _put(self, entity: EntityState) -> None:
        assert self.path is not None
        x, y, z, heading = self.path.pose_at(self.s)
        entity.x, entity.y, entity.z = x, y, z
        entity.heading = float(math.remainder(heading, math.tau))
        entity.lane = -1
