"""The lane-graph map: lanes, signals, crosswalks, sidewalks and queries over them."""

from __future__ import annotations

import copy
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field, fields, is_dataclass

import numpy as np
import numpy.typing as npt

from egosim.world import kernels
from egosim.world.arrays import FloatArray, IntArray
from egosim.world.kernels.lane_poses import lane_poses
from egosim.world.map.errors import MapGeometryError, UnknownLaneError
from egosim.world.map.georef import GeoReference
from egosim.world.map.light_type import LightType
from egosim.world.map.polyline import segment_headings, stations
from egosim.world.map.projection import (
    LaneProjection,
    LaneProjections,
    ProjectionMemory,
    SegmentTable,
)
from egosim.world.map.road_coordinates import RoadCoordinates
from egosim.world.map.road_marking import RoadMarking

# Gap between lanes on the flattened station axis, so a station never reaches the next lane.
_LANE_KEY_GAP_M = 1.0


def _frozen_array(values: object, what: str) -> FloatArray:
    array = np.array(values, dtype=np.float64)
    if not np.all(np.isfinite(array)):
        raise MapGeometryError(f"{what} holds non-finite values")
    array.flags.writeable = False
    return array


_NOT_MOVED = np.empty(0)
_NO_HINTS = np.empty(0, np.int64)
"""No search hints: every point's search goes over the whole centreline table."""


class _ArrayFieldsEquality:
    """Dataclass equality that compares numpy arrays by value (for eq=False dataclasses)."""

    def __eq__(self, other: object) -> bool:
        if type(self) is not type(other) or not is_dataclass(self):
            return NotImplemented
        for f in fields(self):
            x, y = getattr(self, f.name), getattr(other, f.name)
            same = np.array_equal(x, y) if isinstance(x, np.ndarray) else x == y
            if not same:
                return False
        return True

    # Unhashable, as an eq=True dataclass is (typeshed types __hash__ as a method only).
    __hash__ = None  # type: ignore[assignment]


@dataclass(frozen=True, eq=False)
class Lane(_ArrayFieldsEquality):
    """One directed lane. Station s runs from 0 at the first centreline point to `length`."""

    id: str
    centerline: FloatArray
    widths: FloatArray
    speed_limit: float
    successors: tuple[str, ...] = ()
    predecessors: tuple[str, ...] = ()
    left_neighbor: str | None = None
    right_neighbor: str | None = None
    stop_line_s: float | None = None
    traffic_light_ids: tuple[str, ...] = ()
    """Every signal head governing the stop line, in the map's order; a driver reads them
    together (egosim.world.signals.lane_signals), GetTrafficLightStatus names the nearest."""
    is_junction: bool = False
    stations: FloatArray = field(init=False, repr=False)
    length: float = field(init=False)

    def __post_init__(self) -> None:
        points = np.asarray(self.centerline, dtype=np.float64)
        if points.ndim != 2 or points.shape[0] < 2 or points.shape[1] not in (2, 3):
            raise MapGeometryError(f"lane {self.id}: centerline must be (N >= 2, 3)")
        if points.shape[1] == 2:
            points = np.column_stack((points, np.zeros(len(points))))
        widths = np.broadcast_to(np.asarray(self.widths, dtype=np.float64), (len(points),))
        if np.any(widths <= 0.0):
            raise MapGeometryError(f"lane {self.id}: widths must be positive")
        station = stations(points)
        if np.any(np.diff(station) <= 1e-9):
            raise MapGeometryError(f"lane {self.id}: centerline repeats a point")
        object.__setattr__(self, "centerline", _frozen_array(points, f"lane {self.id}"))
        object.__setattr__(self, "widths", _frozen_array(widths, f"lane {self.id} widths"))
        object.__setattr__(self, "stations", _frozen_array(station, f"lane {self.id}"))
        object.__setattr__(self, "length", float(station[-1]))
        if self.stop_line_s is not None and not 0.0 <= self.stop_line_s <= self.length:
            raise MapGeometryError(f"lane {self.id}: stop line outside the lane")


@dataclass(frozen=True)
class TrafficLightSite:
    """A signal head. `id` is the protocol's trafficLightIndex."""

    id: str
    position: tuple[float, float, float]
    heading: float
    light_type: LightType
    lane_ids: tuple[str, ...]
    intersection_id: int


@dataclass(frozen=True)
class IntersectionSite:
    """A signalised junction. Lights in one approach group always show the same aspect."""

    id: int
    center: tuple[float, float]
    light_ids: tuple[str, ...]
    approach_groups: tuple[tuple[str, ...], ...]


@dataclass(frozen=True)
class Crosswalk:
    """A zebra crossing from `start` to `end` (the walking direction), `width` m wide."""

    id: str
    start: tuple[float, float]
    end: tuple[float, float]
    width: float
    intersection_id: int | None


@dataclass(frozen=True, eq=False)
class Sidewalk(_ArrayFieldsEquality):
    """A polyline pedestrians walk along; closed when the last point equals the first."""

    id: str
    points: FloatArray

    def __post_init__(self) -> None:
        object.__setattr__(self, "points", _frozen_array(self.points, f"sidewalk {self.id}"))


class LaneMap:
    """A road network in a local ENU frame (x east, y north, z up, metres)."""

    def __init__(
        self,
        name: str,
        lanes: Iterable[Lane],
        traffic_lights: Iterable[TrafficLightSite],
        intersections: Iterable[IntersectionSite],
        crosswalks: Iterable[Crosswalk],
        sidewalks: Iterable[Sidewalk],
        georef: GeoReference,
    ) -> None:
        self.name = name
        lanes = list(lanes)
        self.lanes: dict[str, Lane] = {lane.id: lane for lane in lanes}
        if len(self.lanes) != len(lanes):
            raise MapGeometryError(f"map {name} repeats lane ids")
        if not self.lanes:
            raise MapGeometryError(f"map {name} has no lanes")
        self.traffic_lights: dict[str, TrafficLightSite] = {t.id: t for t in traffic_lights}
        self.intersections: dict[int, IntersectionSite] = {i.id: i for i in intersections}
        self.crosswalks: dict[str, Crosswalk] = {c.id: c for c in crosswalks}
        self.sidewalks: dict[str, Sidewalk] = {s.id: s for s in sidewalks}
        self.georef = georef
        self.markings: tuple[RoadMarking, ...] = ()
        """Paint the map's data lists (empty: see egosim.world.map.markings)."""
        self.roads: RoadCoordinates | None = None
        """The roads the lanes were built from (OpenDRIVE's), None for a map of lanes
        only (see egosim.world.map.lane_roads)."""
        self.lane_ids: tuple[str, ...] = tuple(self.lanes)
        self._index = {lane_id: i for i, lane_id in enumerate(self.lane_ids)}
        self._check_references()

        ordered = [self.lanes[i] for i in self.lane_ids]
        self.lane_lengths: FloatArray = np.array([lane.length for lane in ordered])
        self._segments = SegmentTable(
            self.lane_ids,
            [lane.centerline for lane in ordered],
            [lane.stations for lane in ordered],
            [lane.widths for lane in ordered],
        )
        counts = np.array([len(lane.centerline) for lane in ordered])
        self._first_point = np.concatenate(([0], np.cumsum(counts)[:-1]))
        self._last_segment = self._first_point + counts - 2
        self._points = np.concatenate([lane.centerline for lane in ordered])
        self._point_station = np.concatenate([lane.stations for lane in ordered])
        # Heading of the segment starting at each point; a lane's last point starts none.
        self._point_heading = np.concatenate(
            [np.append(segment_headings(lane.centerline), np.nan) for lane in ordered]
        )
        self._lane_key_base = np.concatenate(
            ([0.0], np.cumsum(self.lane_lengths + _LANE_KEY_GAP_M)[:-1])
        )
        self._point_key = np.repeat(self._lane_key_base, counts) + self._point_station

    def with_crosswalks(self, crosswalks: Iterable[Crosswalk]) -> LaneMap:
        """This map with `crosswalks` added; lanes and their indexes are shared, not rebuilt
        (a loader that squares crosswalks to the lanes needs the lanes built first)."""
        result = copy.copy(self)
        result.crosswalks = {**self.crosswalks, **{c.id: c for c in crosswalks}}
        return result

    def with_markings(self, markings: Iterable[RoadMarking]) -> LaneMap:
        """This map with the road markings its data lists; lanes and indexes are shared."""
        result = copy.copy(self)
        result.markings = tuple(markings)
        return result

    def with_roads(self, roads: RoadCoordinates) -> LaneMap:
        """This map with the road coordinates of the data it was built from."""
        result = copy.copy(self)
        result.roads = roads
        return result

    def _check_references(self) -> None:
        for lane in self.lanes.values():
            named = (*lane.successors, *lane.predecessors, lane.left_neighbor, lane.right_neighbor)
            missing = [i for i in named if i is not None and i not in self.lanes]
            if missing:
                raise MapGeometryError(f"lane {lane.id} refers to unknown lanes {missing}")
            unknown = [i for i in lane.traffic_light_ids if i not in self.traffic_lights]
            if unknown:
                raise MapGeometryError(f"lane {lane.id}: unknown light {', '.join(unknown)}")

    def lane_index(self, lane_id: str) -> int:
        try:
            return self._index[lane_id]
        except KeyError:
            raise UnknownLaneError(lane_id) from None

    def lane(self, lane_id: str) -> Lane:
        try:
            return self.lanes[lane_id]
        except KeyError:
            raise UnknownLaneError(lane_id) from None

    def project(self, x: float, y: float, heading: float | None = None) -> LaneProjection:
        """The lane a point belongs to; `heading` (rad) prefers lanes within ±90° of it."""
        hint = None if heading is None else np.array([heading], dtype=np.float64)
        return self.project_many(np.array([[x, y]], dtype=np.float64), hint)[0]

    def project_many(
        self,
        xy: npt.ArrayLike,
        headings: npt.ArrayLike | None = None,
        memory: ProjectionMemory | None = None,
    ) -> LaneProjections:
        """`project` for an (N, 2) array of points (and optional (N,) heading hints, NaN
        where a point has none). A caller projecting the same points over and over (an
        agent at rest stays where it was) may keep a `memory` of its own between calls."""
        points = np.asarray(xy, dtype=np.float64).reshape(-1, 2)
        hint = None if headings is None else np.asarray(headings, dtype=np.float64).reshape(-1)
        return self._segments.project(points, hint, memory)

    def pose_at(self, lane_id: str, s: float) -> tuple[float, float, float, float]:
        """(x, y, z, heading) on the centreline at station s, clamped to [0, length]."""
        x, y, z, heading = self.poses_at(np.array([self.lane_index(lane_id)]), np.array([s]))[0]
        return float(x), float(y), float(z), float(heading)

    def poses_at(
        self,
        lane_indices: npt.ArrayLike,
        s: npt.ArrayLike,
        lateral: FloatArray | None = None,
        search_hints: IntArray | None = None,
    ) -> FloatArray:
        """(N, 4) array of x, y, z, heading for lane indices and stations (clamped); with
        `lateral`, each point moved that far (m) to the left of its lane. A caller asking
        for the same agents step after step may keep (N,) `search_hints` of its own:
        where the search along the centrelines ended for each point last time (any
        values will do; updated in place), so that the next search starts there."""
        lanes = np.asarray(lane_indices, dtype=np.int64).reshape(-1)
        stations = np.asarray(s, dtype=np.float64).reshape(-1)
        if kernels.ACTIVE:
            return lane_poses(
                lanes,
                stations,
                _NOT_MOVED if lateral is None else lateral,
                _NO_HINTS if search_hints is None else search_hints,
                self.lane_lengths,
                self._lane_key_base,
                self._point_key,
                self._first_point,
                self._last_segment,
                self._point_station,
                self._points,
                self._point_heading,
            )
        # minimum(maximum()) rather than np.clip: the same values, a fraction of the
        # overhead on the few elements a step asks for.
        station = np.minimum(np.maximum(stations, 0.0), self.lane_lengths[lanes])
        j = np.searchsorted(self._point_key, self._lane_key_base[lanes] + station, side="right") - 1
        j = np.minimum(np.maximum(j, self._first_point[lanes]), self._last_segment[lanes])
        span = self._point_station[j + 1] - self._point_station[j]
        t = ((station - self._point_station[j]) / span)[:, None]
        xyz = self._points[j] + t * (self._points[j + 1] - self._points[j])
        pose = np.concatenate((xyz, self._point_heading[j, None]), axis=1)
        if lateral is not None:
            heading = pose[:, 3].copy()
            pose[:, 0] -= lateral * np.sin(heading)
            pose[:, 1] += lateral * np.cos(heading)
        return pose

    def lookahead(
        self, lane_id: str, s: float, distance: float, route: Sequence[str] = ()
    ) -> FloatArray:
        """(M, 2) centreline points from (lane_id, s) onward over `distance` metres.

        At each lane end the path continues on the earliest not-yet-used `route` lane that
        is a successor, else on the first successor; it stops early at a dead end.
        """
        lane = self.lane(lane_id)
        start = min(max(s, 0.0), lane.length)
        remaining = distance
        pieces = [np.array([self.pose_at(lane_id, start)[:2]])]
        route_pos = 0
        while True:
            end = min(lane.length, start + remaining)
            inside = (lane.stations > start) & (lane.stations < end)
            pieces.append(lane.centerline[inside, :2])
            pieces.append(np.array([self.pose_at(lane.id, end)[:2]]))
            remaining -= end - start
            if remaining <= 1e-9 or not lane.successors:
                break
            next_id, route_pos = _next_lane(lane.successors, route, route_pos)
            lane, start = self.lanes[next_id], 0.0
        path = np.concatenate(pieces)
        step = np.hypot(*np.diff(path, axis=0).T)
        return path[np.concatenate(([True], step > 1e-9))]

    def bounds(self) -> tuple[float, float, float, float]:
        """(xmin, ymin, xmax, ymax) holding every lane: centreline points padded by half width."""
        half = np.concatenate([lane.widths for lane in self.lanes.values()])[:, None] / 2.0
        lo = (self._points[:, :2] - half).min(axis=0)
        hi = (self._points[:, :2] + half).max(axis=0)
        return float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1])


def _next_lane(
    successors: tuple[str, ...], route: Sequence[str], route_pos: int
) -> tuple[str, int]:
    for k in range(route_pos, len(route)):
        if route[k] in successors:
            return route[k], k + 1
    return successors[0], route_pos


__all__ = [
    "Crosswalk",
    "IntersectionSite",
    "Lane",
    "LaneMap",
    "LaneProjection",
    "LaneProjections",
    "Sidewalk",
    "TrafficLightSite",
]
