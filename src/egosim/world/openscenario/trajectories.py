"""Trajectories: polylines, clothoids (1.0–1.2), clothoid splines (1.3) and NURBS,
sampled into paths on the map when an action or a position needs them.

A shape whose start is not given (a clothoid without its <Position>) starts where the
following entity stands. Vertex and control-point times become the path's times
(FollowTrajectoryAction with a <Timing> follows them). Paths made only of absolute
positions are sampled once and kept.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from egosim.world.openscenario.entities import EntityState
from egosim.world.openscenario.geometry_path import SampledPath
from egosim.world.openscenario.positions import (
    GeoPosition,
    LanePosition,
    Placement,
    Position,
    PositionError,
    RoadPosition,
    WorldPosition,
)
from egosim.world.openscenario.runtime import Runtime
from egosim.world.openscenario.xmltree import Node

CLOTHOID_STEP_M = 0.1
NURBS_SAMPLES_PER_SPAN = 50
_ABSOLUTE = (WorldPosition, GeoPosition, LanePosition, RoadPosition)


@dataclass(frozen=True)
class Vertex:
    position: Position
    time: float | None = None


@dataclass(frozen=True)
class Polyline:
    vertices: tuple[Vertex, ...]

    def positions(self) -> list[Position]:
        return [v.position for v in self.vertices]

    def sample(self, rt: Runtime, start: Placement | None) -> SampledPath:
        placed = [v.position.resolve(rt) for v in self.vertices]
        points = np.array([(p.x, p.y, p.z) for p in placed])
        times = [v.time for v in self.vertices]
        timed = all(t is not None for t in times)
        return SampledPath.through(points, np.array(times, dtype=np.float64) if timed else None)


@dataclass(frozen=True)
class ClothoidSegment:
    """A piece of constant curvature rate: curvature from `start` to `end` over length."""

    curvature_start: float
    curvature_end: float
    length: float
    heading_offset: float = 0.0
    time_start: float | None = None
    position: Position | None = None


def _integrate(
    x: float, y: float, z: float, heading: float, segment: ClothoidSegment
) -> tuple[np.ndarray, np.ndarray]:
    """Points (N, 3) and headings (N,) along one clothoid piece, its start included."""
    steps = max(math.ceil(segment.length / CLOTHOID_STEP_M), 1)
    u = np.linspace(0.0, segment.length, steps + 1)
    rate = (segment.curvature_end - segment.curvature_start) / max(segment.length, 1e-12)
    headings = heading + segment.curvature_start * u + 0.5 * rate * u**2
    # Midpoint rule over each step: the heading halfway along it.
    mid = 0.5 * (u[:-1] + u[1:])
    mid_heading = heading + segment.curvature_start * mid + 0.5 * rate * mid**2
    du = np.diff(u)
    xs = x + np.concatenate(([0.0], np.cumsum(du * np.cos(mid_heading))))
    ys = y + np.concatenate(([0.0], np.cumsum(du * np.sin(mid_heading))))
    return np.column_stack((xs, ys, np.full(len(u), z))), headings


@dataclass(frozen=True)
class ClothoidSpline:
    segments: tuple[ClothoidSegment, ...]
    time_end: float | None = None

    def positions(self) -> list[Position]:
        return [s.position for s in self.segments if s.position is not None]

    def sample(self, rt: Runtime, start: Placement | None) -> SampledPath:
        points: list[np.ndarray] = []
        headings: list[np.ndarray] = []
        pose = start
        for segment in self.segments:
            if segment.position is not None:
                pose = segment.position.resolve(rt)
            if pose is None:
                raise PositionError("the clothoid's start is not given and no entity follows it")
            heading = pose.heading + segment.heading_offset
            piece, piece_headings = _integrate(pose.x, pose.y, pose.z, heading, segment)
            skip = 1 if points else 0
            points.append(piece[skip:])
            headings.append(piece_headings[skip:])
            x, y, z = piece[-1]
            pose = Placement(float(x), float(y), float(z), float(piece_headings[-1]))
        path = SampledPath.through(np.concatenate(points), headings=np.concatenate(headings))
        return _timed_spline(path, self.segments, self.time_end)


def _timed_spline(
    path: SampledPath, segments: tuple[ClothoidSegment, ...], time_end: float | None
) -> SampledPath:
    """Times at every point when each segment has its start time (and the spline its end
    time): linear in distance within each segment."""
    starts = [s.time_start for s in segments]
    if time_end is None or any(t is None for t in starts):
        return path
    knots_s = np.concatenate(([0.0], np.cumsum([s.length for s in segments])))
    knots_t = np.array([*starts, time_end], dtype=np.float64)
    times = np.interp(path.s, knots_s, knots_t)
    return SampledPath(path.points, path.s, path.headings, times)


@dataclass(frozen=True)
class Clothoid:
    """The 1.0–1.2 single clothoid: curvature, its rate, length, optional start."""

    curvature: float
    curvature_prime: float
    length: float
    start_time: float | None
    stop_time: float | None
    position: Position | None

    def positions(self) -> list[Position]:
        return [] if self.position is None else [self.position]

    def sample(self, rt: Runtime, start: Placement | None) -> SampledPath:
        segment = ClothoidSegment(
            self.curvature,
            self.curvature + self.curvature_prime * self.length,
            self.length,
            0.0,
            self.start_time,
            self.position,
        )
        return ClothoidSpline((segment,), self.stop_time).sample(rt, start)


@dataclass(frozen=True)
class ControlPoint:
    position: Position
    weight: float = 1.0
    time: float | None = None


@dataclass(frozen=True)
class Nurbs:
    order: int
    control_points: tuple[ControlPoint, ...]
    knots: tuple[float, ...]

    def positions(self) -> list[Position]:
        return [c.position for c in self.control_points]

    def sample(self, rt: Runtime, start: Placement | None) -> SampledPath:
        placed = [c.position.resolve(rt) for c in self.control_points]
        control = np.array([(p.x, p.y, p.z) for p in placed])
        weights = np.array([c.weight for c in self.control_points])
        times = [c.time for c in self.control_points]
        knots = np.array(self.knots, dtype=np.float64)
        degree = self.order - 1
        lo, hi = knots[degree], knots[len(control)]
        u = np.linspace(lo, hi, NURBS_SAMPLES_PER_SPAN * max(len(control) - degree, 1) + 1)
        basis = _basis(knots, degree, len(control), u) * weights
        basis /= np.maximum(basis.sum(axis=1, keepdims=True), 1e-12)
        points = basis @ control
        timed = None
        if all(t is not None for t in times):
            timed = basis @ np.array(times, dtype=np.float64)
        return SampledPath.through(points, timed)


def _basis(knots: np.ndarray, degree: int, count: int, u: np.ndarray) -> np.ndarray:
    """B-spline basis functions N_{i,degree}(u), (len(u), count), Cox–de Boor."""
    last = knots[count]
    u = np.minimum(u, last - 1e-12 * max(1.0, abs(last)))
    n = np.array(
        [(knots[i] <= u) & (u < knots[i + 1]) for i in range(len(knots) - 1)], dtype=np.float64
    ).T
    for p in range(1, degree + 1):
        nxt = np.zeros((len(u), len(knots) - 1 - p))
        for i in range(len(knots) - 1 - p):
            left_span = knots[i + p] - knots[i]
            right_span = knots[i + p + 1] - knots[i + 1]
            if left_span > 0:
                nxt[:, i] += (u - knots[i]) / left_span * n[:, i]
            if right_span > 0:
                nxt[:, i] += (knots[i + p + 1] - u) / right_span * n[:, i + 1]
        n = nxt
    basis: np.ndarray = n[:, :count]
    return basis


Shape = Polyline | Clothoid | ClothoidSpline | Nurbs


@dataclass(frozen=True)
class Trajectory:
    node: Node
    name: str
    closed: bool
    shape: Shape
    _cache: dict[str, SampledPath] = field(default_factory=dict, compare=False, repr=False)

    def _fixed(self) -> bool:
        needs_start = isinstance(self.shape, (Clothoid, ClothoidSpline)) and (
            not self.shape.positions()
            or (isinstance(self.shape, ClothoidSpline) and self.shape.segments[0].position is None)
        )
        return not needs_start and all(isinstance(p, _ABSOLUTE) for p in self.shape.positions())

    def path(self, rt: Runtime, entity: EntityState | None) -> SampledPath:
        fixed = self._fixed()
        if fixed and "path" in self._cache:
            return self._cache["path"]
        start = None
        if entity is not None and entity.placed:
            start = Placement(entity.x, entity.y, entity.z, entity.heading)
        path = self.shape.sample(rt, start)
        if self.closed and len(path.points) > 1:
            points = np.vstack((path.points, path.points[:1]))
            path = SampledPath.through(points)
        if fixed:
            self._cache["path"] = path
        return path
