"""Distances between entities and positions as OpenSCENARIO measures them: Euclidean
(cartesian), longitudinal or lateral; between reference points or between bounding
boxes (freespace); in the entity's frame, or along the road or lane.
"""

from __future__ import annotations

import math

import numpy as np

from egosim.world.map.road_coordinates import UnknownRoadError
from egosim.world.openscenario.entities import EntityState
from egosim.world.openscenario.lane_paths import distance_along
from egosim.world.openscenario.runtime import Runtime

EUCLIDEAN = ("euclidianDistance", "euclideanDistance", "cartesianDistance")
DISTANCE_TYPES = (*EUCLIDEAN, "longitudinal", "lateral")
COORDINATE_SYSTEMS = ("entity", "lane", "road", "trajectory", "world")


def corners(entity: EntityState) -> np.ndarray:
    """(4, 2) corners of the entity's bounding box."""
    cx, cy = entity.box_centre()
    half_l, half_w = entity.definition.length / 2.0, entity.definition.width / 2.0
    c, s = math.cos(entity.heading), math.sin(entity.heading)
    local = np.array([(half_l, half_w), (half_l, -half_w), (-half_l, -half_w), (-half_l, half_w)])
    return np.column_stack(
        (cx + local[:, 0] * c - local[:, 1] * s, cy + local[:, 0] * s + local[:, 1] * c)
    )


def _segment_distance(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> float:
    d = b - a
    f = float(np.clip(np.dot(p - a, d) / max(float(np.dot(d, d)), 1e-12), 0.0, 1.0))
    return float(np.hypot(*(p - (a + f * d))))


def _inside(p: np.ndarray, box: np.ndarray) -> bool:
    signs = []
    for k in range(4):
        a, b = box[k], box[(k + 1) % 4]
        signs.append((b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]))
    return all(s >= -1e-12 for s in signs) or all(s <= 1e-12 for s in signs)


def point_gap(point: np.ndarray, box: np.ndarray) -> float:
    """Distance from a point to a convex polygon; 0 inside it."""
    if _inside(point, box):
        return 0.0
    return min(_segment_distance(point, box[k], box[(k + 1) % len(box)]) for k in range(len(box)))


def box_gap(a: np.ndarray, b: np.ndarray) -> float:
    """Shortest distance between two convex polygons ((N, 2) points); 0 when they touch."""
    if any(_inside(p, b) for p in a) or any(_inside(p, a) for p in b):
        return 0.0
    best = math.inf
    for poly, other in ((a, b), (b, a)):
        for p in poly:
            for k in range(len(other)):
                best = min(best, _segment_distance(p, other[k], other[(k + 1) % len(other)]))
    return best


def _interval_gap(axis: np.ndarray, a: np.ndarray, b: np.ndarray) -> float:
    """Signed gap along `axis` between the projections of two point sets: positive when
    b lies ahead of a, negative behind, 0 where they overlap."""
    pa, pb = a @ axis, b @ axis
    if pb.min() >= pa.max():
        return float(pb.min() - pa.max())
    if pa.min() >= pb.max():
        return -float(pa.min() - pb.max())
    return 0.0


def _points(entity: EntityState, freespace: bool) -> np.ndarray:
    return corners(entity) if freespace else np.array([[entity.x, entity.y]])


def relative(
    rt: Runtime,
    entity: EntityState,
    other: EntityState | tuple[float, float],
    distance_type: str,
    freespace: bool,
    coordinate_system: str = "entity",
) -> float:
    """Signed distance from `entity` to `other` (an entity or a point): longitudinal is
    positive ahead of the entity, lateral positive to its left, Euclidean never negative."""
    mine = _points(entity, freespace)
    theirs = _points(other, freespace) if isinstance(other, EntityState) else np.array([other])
    if distance_type in EUCLIDEAN:
        if freespace and len(theirs) > 1:
            return box_gap(mine, theirs)
        if freespace:
            return point_gap(theirs[0], mine)
        return float(np.hypot(*(theirs[0] - mine[0])))
    if coordinate_system in ("road", "lane") and isinstance(other, EntityState):
        along = _along_lanes(rt, entity, other, distance_type, freespace)
        if along is not None:
            return along
    heading = entity.heading
    axis = (
        np.array([math.cos(heading), math.sin(heading)])
        if distance_type == "longitudinal"
        else np.array([-math.sin(heading), math.cos(heading)])
    )
    if freespace:
        return _interval_gap(axis, mine, theirs)
    return float((theirs[0] - mine[0]) @ axis)


def _along_lanes(
    rt: Runtime, entity: EntityState, other: EntityState, distance_type: str, freespace: bool
) -> float | None:
    if entity.lane < 0 or other.lane < 0:
        return None
    if distance_type == "lateral":
        try:
            mine = rt.roads.locate(entity.lane, entity.station, entity.offset)
            theirs = rt.roads.locate(other.lane, other.station, other.offset)
        except UnknownRoadError:
            return None
        if mine.road != theirs.road:
            return None
        sign = 1.0 if rt.roads.forward(entity.lane) else -1.0
        gap = sign * (theirs.t - mine.t)
        if freespace:
            reach = (entity.definition.width + other.definition.width) / 2.0
            return math.copysign(max(abs(gap) - reach, 0.0), gap)
        return gap
    along = distance_along(rt.lane_map, entity.lane, entity.station, other.lane, other.station)
    if along is None:
        # Lanes side by side: the other's station carried onto this lane.
        beside = rt.lane_map.lanes[rt.lane_map.lane_ids[entity.lane]]
        if rt.lane_map.lane_ids[other.lane] not in (beside.left_neighbor, beside.right_neighbor):
            return None
        along = other.station - entity.station
    if freespace:
        reach = (entity.definition.length + other.definition.length) / 2.0
        return math.copysign(max(abs(along) - reach, 0.0), along)
    return along


def time_headway(
    rt: Runtime,
    entity: EntityState,
    leader: EntityState,
    freespace: bool,
    coordinate_system: str = "entity",
) -> float:
    """Time (s) the entity needs at its speed to reach where the leader is now; inf when
    the leader is not ahead or the entity does not move towards it."""
    gap = relative(rt, entity, leader, "longitudinal", freespace, coordinate_system)
    if gap < 0.0 or entity.speed <= 0.0:
        return math.inf
    return gap / entity.speed


def time_to_collision(
    rt: Runtime,
    entity: EntityState,
    target: EntityState | tuple[float, float],
    freespace: bool,
    distance_type: str = "longitudinal",
    coordinate_system: str = "entity",
) -> float:
    """Time (s) until the entity reaches the target at the speeds of now; inf when it is
    not closing in."""
    if distance_type in EUCLIDEAN:
        gap = relative(rt, entity, target, distance_type, freespace, coordinate_system)
        if isinstance(target, EntityState):
            dx, dy = target.x - entity.x, target.y - entity.y
            rv = _velocity(target) - _velocity(entity)
        else:
            dx, dy = target[0] - entity.x, target[1] - entity.y
            rv = -_velocity(entity)
        norm = math.hypot(dx, dy)
        closing = -(rv @ np.array([dx, dy])) / norm if norm > 0 else 0.0
    else:
        gap = relative(rt, entity, target, distance_type, freespace, coordinate_system)
        heading = entity.heading
        axis = np.array([math.cos(heading), math.sin(heading)])
        if distance_type == "lateral":
            axis = np.array([-math.sin(heading), math.cos(heading)])
        other = _velocity(target) if isinstance(target, EntityState) else np.zeros(2)
        closing = float((_velocity(entity) - other) @ axis) * (1.0 if gap >= 0 else -1.0)
        gap = abs(gap)
    if closing <= 1e-9:
        return math.inf
    return gap / closing


def _velocity(entity: EntityState) -> np.ndarray:
    return entity.speed * np.array([math.cos(entity.heading), math.sin(entity.heading)])
