"""OpenSCENARIO positions, read at load time, placed on the map when used.

Each position is resolved against the running scenario (its entities move) into a
Placement: the entity's reference point, its heading and, where the position names one,
the lane it stands on. Orientation: a LanePosition faces its lane's travel direction and
a RoadPosition its road's reference direction unless an <Orientation> says otherwise
(`relative` adds to that direction, `absolute` replaces it); the relative positions
face the referenced entity's heading.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Protocol

import numpy as np

from egosim.world.map.road_coordinates import LanePlace, UnknownRoadError
from egosim.world.openscenario.entities import EntityState
from egosim.world.openscenario.geometry_path import SampledPath
from egosim.world.openscenario.lane_paths import advance
from egosim.world.openscenario.runtime import Runtime
from egosim.world.openscenario.xmltree import Node

FOLLOWS_LANE_COS = math.cos(math.radians(60.0))
"""An entity placed within 60 degrees of a lane's direction follows that lane."""


class PositionError(ValueError):
    """A position that cannot be placed now; the message names it and why."""


@dataclass(frozen=True)
class Placement:
    x: float
    y: float
    z: float
    heading: float
    lane: LanePlace | None = None


@dataclass(frozen=True)
class Orientation:
    kind: str | None = None
    """"relative", "absolute" or None (no <Orientation>)."""
    h: float = 0.0

    def heading(self, base: float) -> float:
        if self.kind == "absolute":
            return self.h
        return base + self.h


class PathSource(Protocol):
    """A trajectory, placed when needed (it may start where an entity stands)."""

    @property
    def node(self) -> Node: ...

    def path(self, rt: Runtime, entity: EntityState | None) -> SampledPath: ...


@dataclass(frozen=True)
class RouteLanes:
    """A route laid on the lanes: lane indices in order, from `start` m into the first."""

    lanes: tuple[int, ...]
    start: float = 0.0

    def place(self, rt: Runtime, path_s: float) -> tuple[int, float]:
        """(lane, station) `path_s` m along the route."""
        lengths = rt.lane_map.lane_lengths
        remaining = self.start + path_s
        for k, lane in enumerate(self.lanes):
            length = float(lengths[lane])
            if remaining <= length or k == len(self.lanes) - 1:
                return lane, min(max(remaining, 0.0), length)
            remaining -= length
        raise PositionError("an empty route")


class RouteSource(Protocol):
    @property
    def node(self) -> Node: ...

    def lanes(self, rt: Runtime) -> RouteLanes: ...


def lane_pose(rt: Runtime, place: LanePlace) -> tuple[float, float, float, float]:
    x, y, z, heading = rt.lane_map.poses_at([place.lane_index], [place.station])[0]
    return (
        float(x - place.offset * math.sin(heading)),
        float(y + place.offset * math.cos(heading)),
        float(z),
        float(heading),
    )


def on_lane(rt: Runtime, place: LanePlace, orientation: Orientation) -> Placement:
    x, y, z, heading = lane_pose(rt, place)
    return Placement(x, y, z, orientation.heading(heading), place)


def _referenced(rt: Runtime, name: str) -> EntityState:
    entity = rt.entities.get(name)
    if entity is None or not entity.placed:
        raise PositionError(f"entity {name!r} has no position yet")
    return entity


@dataclass(frozen=True)
class WorldPosition:
    node: Node
    x: float
    y: float
    z: float = 0.0
    h: float = 0.0

    def resolve(self, rt: Runtime) -> Placement:
        return Placement(self.x, self.y, self.z, self.h)


@dataclass(frozen=True)
class GeoPosition:
    node: Node
    latitude_deg: float
    longitude_deg: float
    altitude: float
    orientation: Orientation

    def resolve(self, rt: Runtime) -> Placement:
        x, y, z = rt.lane_map.georef.geodetic_to_local(
            self.latitude_deg, self.longitude_deg, self.altitude
        )
        return Placement(float(x), float(y), float(z), self.orientation.heading(0.0))


@dataclass(frozen=True)
class RelativeWorldPosition:
    node: Node
    entity: str
    dx: float
    dy: float
    dz: float
    orientation: Orientation

    def resolve(self, rt: Runtime) -> Placement:
        ref = _referenced(rt, self.entity)
        heading = self.orientation.heading(ref.heading)
        return Placement(ref.x + self.dx, ref.y + self.dy, ref.z + self.dz, heading)


@dataclass(frozen=True)
class RelativeObjectPosition:
    node: Node
    entity: str
    dx: float
    dy: float
    dz: float
    orientation: Orientation

    def resolve(self, rt: Runtime) -> Placement:
        ref = _referenced(rt, self.entity)
        c, s = math.cos(ref.heading), math.sin(ref.heading)
        x = ref.x + c * self.dx - s * self.dy
        y = ref.y + s * self.dx + c * self.dy
        return Placement(x, y, ref.z + self.dz, self.orientation.heading(ref.heading))


def _road_placement(
    rt: Runtime, road: str, s: float, t: float, orientation: Orientation
) -> Placement:
    try:
        x, y, z, heading = rt.roads.pose(road, s, t)
    except UnknownRoadError as error:
        raise PositionError(str(error)) from None
    return Placement(x, y, z, orientation.heading(heading))


@dataclass(frozen=True)
class RoadPosition:
    node: Node
    road: str
    s: float
    t: float
    orientation: Orientation

    def resolve(self, rt: Runtime) -> Placement:
        return _road_placement(rt, self.road, self.s, self.t, self.orientation)


def entity_road_point(rt: Runtime, entity: EntityState) -> tuple[str, int, float, float]:
    """(road, lane, s, t) of an entity on a lane."""
    if entity.lane < 0:
        raise PositionError(f"entity {entity.name!r} is on no lane")
    try:
        point = rt.roads.locate(entity.lane, entity.station, entity.offset)
    except UnknownRoadError as error:
        raise PositionError(str(error)) from None
    return point.road, point.lane, point.s, point.t


@dataclass(frozen=True)
class RelativeRoadPosition:
    node: Node
    entity: str
    ds: float
    dt: float
    orientation: Orientation

    def resolve(self, rt: Runtime) -> Placement:
        ref = _referenced(rt, self.entity)
        road, _, s, t = entity_road_point(rt, ref)
        return _road_placement(rt, road, s + self.ds, t + self.dt, self.orientation)


@dataclass(frozen=True)
class LanePosition:
    node: Node
    road: str
    lane: int
    s: float
    offset: float
    orientation: Orientation

    def resolve(self, rt: Runtime) -> Placement:
        try:
            place = rt.roads.lane_place(self.road, self.lane, self.s, self.offset)
        except UnknownRoadError:
            # A lane egosim does not drive on (a shoulder, a sidewalk): on the road alone.
            try:
                t = rt.roads.lane_centre_t(self.road, self.lane, self.s)
            except UnknownRoadError as error:
                raise PositionError(str(error)) from None
            along = _road_placement(rt, self.road, self.s, t + self.offset, Orientation())
            travel = along.heading + (math.pi if self.lane > 0 else 0.0)
            return Placement(along.x, along.y, along.z, self.orientation.heading(travel))
        return on_lane(rt, place, self.orientation)


def neighbour(rt: Runtime, lane: int, count: int) -> int:
    """The lane `count` lanes to the left (positive) or right of `lane`, by travel
    direction; PositionError where there is none."""
    lane_map = rt.lane_map
    here = lane
    for _ in range(abs(count)):
        record = lane_map.lanes[lane_map.lane_ids[here]]
        beside_id = record.left_neighbor if count > 0 else record.right_neighbor
        if beside_id is None:
            side = "left" if count > 0 else "right"
            raise PositionError(
                f"lane {lane_map.lane_ids[lane]} has no lane {abs(count)} to the {side}"
            )
        here = lane_map.lane_index(beside_id)
    return here


def beside(rt: Runtime, lane: int, station: float, target: int) -> float:
    """The station on lane `target` beside `station` on lane `lane`."""
    lengths = rt.lane_map.lane_lengths
    return float(min(station * lengths[target] / max(lengths[lane], 1e-9), lengths[target]))


@dataclass(frozen=True)
class RelativeLanePosition:
    node: Node
    entity: str
    d_lane: int
    ds: float | None
    ds_lane: float | None
    offset: float
    orientation: Orientation

    def resolve(self, rt: Runtime) -> Placement:
        ref = _referenced(rt, self.entity)
        if ref.lane < 0:
            raise PositionError(f"entity {ref.name!r} is on no lane")
        target = neighbour(rt, ref.lane, self.d_lane)
        station = beside(rt, ref.lane, ref.station, target)
        ds = self.ds_lane if self.ds_lane is not None else (self.ds or 0.0)
        if self.ds_lane is None and not rt.roads.forward(target):
            ds = -ds  # ds runs along the road's reference line, this lane against it
        lane, station, _, _ = advance(
            rt.lane_map, target, station, ds, ref.route, ref.route_position
        )
        offset = self.offset if rt.roads.forward(lane) else -self.offset
        return on_lane(rt, LanePlace(lane, station, offset), self.orientation)


@dataclass(frozen=True)
class TrajectoryPosition:
    node: Node
    trajectory: PathSource
    s: float
    t: float
    orientation: Orientation

    def resolve(self, rt: Runtime) -> Placement:
        path = self.trajectory.path(rt, None)
        x, y, z, heading = path.offset_pose(self.s, self.t)
        return Placement(x, y, z, self.orientation.heading(heading))


@dataclass(frozen=True)
class RoutePosition:
    node: Node
    route: RouteSource
    kind: str
    """"entity", "road" or "lane" (InRoutePosition's choice)."""
    entity: str = ""
    path_s: float = 0.0
    t: float = 0.0
    lane: int = 0
    lane_offset: float = 0.0
    orientation: Orientation = Orientation()

    def resolve(self, rt: Runtime) -> Placement:
        if self.kind == "entity":
            ref = _referenced(rt, self.entity)
            return Placement(ref.x, ref.y, ref.z, self.orientation.heading(ref.heading))
        lane, station = self.route.lanes(rt).place(rt, self.path_s)
        place: LanePlace | None = None
        try:
            point = rt.roads.locate(lane, station, 0.0)
            if self.kind == "lane":
                place = rt.roads.lane_place(point.road, self.lane, point.s, self.lane_offset)
                x, y, z, heading = lane_pose(rt, place)
            else:
                x, y, z, heading = rt.roads.pose(point.road, point.s, self.t)
        except UnknownRoadError as error:
            raise PositionError(str(error)) from None
        if self.orientation.kind is not None:
            # An orientation is to the route's direction of travel there, whichever way
            # the named lane or the road's reference line runs.
            _, _, _, along_route = rt.lane_map.poses_at([lane], [station])[0]
            heading = self.orientation.heading(float(along_route))
        return Placement(float(x), float(y), float(z), float(heading), place)


Position = (
    WorldPosition
    | GeoPosition
    | RelativeWorldPosition
    | RelativeObjectPosition
    | RoadPosition
    | RelativeRoadPosition
    | LanePosition
    | RelativeLanePosition
    | TrajectoryPosition
    | RoutePosition
)


def attach(rt: Runtime, placement: Placement) -> LanePlace | None:
    """The lane a placement stands on and follows: its own, else the lane its point
    projects onto (within half that lane's width plus a metre); None off the lanes or
    facing across the lane (a pedestrian on a crossing path)."""
    lane = placement.lane
    if lane is None or not _follows(rt, lane, placement.heading):
        # Not named, or named but faced against (a LanePosition offset onto the
        # oncoming lane, turned round): the lane its point and heading are on.
        projection = rt.lane_map.project(placement.x, placement.y, placement.heading)
        if abs(projection.lateral) > projection.width / 2.0 + 1.0:
            return None
        index = rt.lane_map.lane_index(projection.lane_id)
        lane = LanePlace(index, projection.s, projection.lateral)
    return lane if _follows(rt, lane, placement.heading) else None


def _follows(rt: Runtime, lane: LanePlace, heading: float) -> bool:
    _, _, _, along = rt.lane_map.poses_at([lane.lane_index], [lane.station])[0]
    return math.cos(heading - float(along)) >= FOLLOWS_LANE_COS


def place(rt: Runtime, entity: EntityState, placement: Placement) -> None:
    """Put an entity where a placement says; from there it moves along the lane it
    stands on, if any. PositionError for a place out of any map (not finite)."""
    if not all(map(math.isfinite, (placement.x, placement.y, placement.z, placement.heading))):
        raise PositionError("it works out to no finite place")
    entity.x, entity.y, entity.z = placement.x, placement.y, placement.z
    entity.heading = float(np.remainder(placement.heading + math.pi, math.tau) - math.pi)
    lane = attach(rt, placement)
    if lane is None:
        entity.lane = -1
    else:
        entity.lane, entity.station, entity.offset = lane.lane_index, lane.station, lane.offset
    entity.placed = True
    entity.teleported = True
