"""Pedestrians walking polylines (sidewalks, crosswalks, scripted waypoints), vectorised.

A walk path may carry gates: stations where the path steps onto a crosswalk. A pedestrian
reaching a gate waits there until that crosswalk's walk signal allows crossing; once on
the crosswalk it keeps walking whatever the lights do (drivers yield to it). A pedestrian
given an activation distance stands where it starts until an ego comes that close to its
wake point (`wake`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from egosim.world import kernels
from egosim.world.arrays import BoolArray, FloatArray, Indices, IntArray
from egosim.world.kernels import pedestrian_motion
from egosim.world.map import Crosswalk, LaneMap, Sidewalk
from egosim.world.traffic.activation import still_dormant
from egosim.world.traffic.catalogue import BoxModel
from egosim.world.traffic.objects import ObjectTable, ObjectType

# Gap between paths on the flattened station axis, so a station never reaches the next path.
_PATH_KEY_GAP_M = 1.0


@dataclass(frozen=True, eq=False)
class WalkPath:
    """An (M, 2) polyline; `closed` paths run back from the last point to the first.
    gates: (station m, crosswalk index) where crossing needs the walk signal; on_road:
    the path may lead onto lanes (sidewalks never do)."""

    points: FloatArray
    closed: bool
    gates: tuple[tuple[float, int], ...] = ()
    on_road: bool = True

    @property
    def loop_points(self) -> FloatArray:
        """The points actually walked: closed paths end on their first point again."""
        points = np.asarray(self.points, dtype=np.float64)
        if self.closed and not np.array_equal(points[0], points[-1]):
            points = np.vstack((points, points[:1]))
        return points

    @property
    def length(self) -> float:
        return float(np.sum(np.hypot(*np.diff(self.loop_points, axis=0).T)))


def sidewalk_path(sidewalk: Sidewalk) -> WalkPath:
    """Along a sidewalk; round and round when it is closed, else to its end."""
    points = sidewalk.points[:, :2]
    return WalkPath(points, closed=bool(np.array_equal(points[0], points[-1])), on_road=False)


def crosswalk_path(crosswalk: Crosswalk, crosswalk_index: int) -> WalkPath:
    """Back and forth over a crosswalk, waiting for the walk signal before each crossing."""
    start, end = np.array(crosswalk.start), np.array(crosswalk.end)
    width = float(np.hypot(*(end - start)))
    return WalkPath(
        np.array([start, end]),
        closed=True,
        gates=((0.0, crosswalk_index), (width, crosswalk_index)),
    )


@dataclass(frozen=True)
class PedestrianSpawn:
    """One pedestrian: walks `path` at `speed` m/s from station `start_s` m, once an ego
    has come within `active_distance` m of `wake_point` (None: where it starts)."""

    unique_id: int
    model: BoxModel
    path: WalkPath
    speed: float
    start_s: float = 0.0
    active_distance: float = math.inf
    wake_point: tuple[float, float] | None = None


class PedestrianCrowd:
    """All pedestrians of a world."""

    def __init__(self) -> None:
        self.clear()

    def clear(self) -> None:
        self._spawns: list[PedestrianSpawn] = []
        self.unique_ids: IntArray = np.empty(0, np.int64)
        self.s: FloatArray = np.empty(0)
        self.stopped: BoolArray = np.empty(0, bool)
        self.dormant: BoolArray = np.empty(0, bool)
        """Per pedestrian: still waiting for an ego to come within its active distance."""
        self.active_distance: FloatArray = np.empty(0)
        self.wake_points: FloatArray = np.empty((0, 2))
        self.shoved: FloatArray = np.empty((0, 2))
        """Per pedestrian: how far contacts pushed them off their path, m (map frame)."""
        self._layout(())
        self.position: FloatArray = np.empty((0, 2))
        self.heading: FloatArray = np.empty(0)
        self.velocity: FloatArray = np.empty((0, 2))
        self.acceleration: FloatArray = np.empty((0, 2))

    def __len__(self) -> int:
        return len(self.unique_ids)

    def spawn(self, spawns: Sequence[PedestrianSpawn]) -> None:
        if not spawns:
            return
        self._spawns += spawns
        self.unique_ids = np.append(self.unique_ids, [p.unique_id for p in spawns])
        self.s = np.append(self.s, [p.start_s for p in spawns])
        self.stopped = np.append(self.stopped, np.zeros(len(spawns), bool))
        self.shoved = np.vstack((self.shoved, np.zeros((len(spawns), 2))))
        self.velocity = np.vstack((self.velocity, np.zeros((len(spawns), 2))))
        self.acceleration = np.vstack((self.acceleration, np.zeros((len(spawns), 2))))
        self._layout(self._spawns)
        self.s = np.clip(self.s, 0.0, self.length)
        position, self.heading = self._place(self.s)
        self.position = position + self.shoved
        distances = [p.active_distance for p in spawns]
        self.active_distance = np.append(self.active_distance, distances)
        self.dormant = np.append(self.dormant, np.isfinite(distances))
        starts = position[len(position) - len(spawns) :]
        wake = [p.wake_point or tuple(start) for p, start in zip(spawns, starts, strict=True)]
        self.wake_points = np.vstack((self.wake_points, np.array(wake, dtype=np.float64)))

    def _layout(self, spawns: Sequence[PedestrianSpawn]) -> None:
        """Flatten every path onto one station axis (keys), with the gates on it."""
        paths = [p.path.loop_points for p in spawns]
        self.names = tuple(p.model.name for p in spawns)
        self.dims = np.array([(p.model.length, p.model.width, p.model.height) for p in spawns])
        self.dims = self.dims.reshape(-1, 3)
        self.walk_speed = np.array([p.speed for p in spawns], dtype=np.float64)
        self.closed: BoolArray = np.array([p.path.closed for p in spawns], dtype=bool)
        self.on_road: BoolArray = np.array([p.path.on_road for p in spawns], dtype=bool)
        steps = [np.hypot(*np.diff(points, axis=0).T) for points in paths]
        self.length = np.array([float(np.sum(step)) for step in steps])
        counts = np.array([len(points) for points in paths], dtype=np.int64)
        self._key_base = np.concatenate(([0.0], np.cumsum(self.length + _PATH_KEY_GAP_M)[:-1]))
        self._key_base = self._key_base[: len(spawns)]
        self._first = np.concatenate(([0], np.cumsum(counts)[:-1]))[: len(spawns)]
        self._last_segment = self._first + counts - 2
        if paths:
            self._points = np.concatenate(paths)
            stations = [np.concatenate(([0.0], np.cumsum(step))) for step in steps]
            self._point_key = np.repeat(self._key_base, counts) + np.concatenate(stations)
            segment_heading = [
                np.append(np.arctan2(np.diff(p[:, 1]), np.diff(p[:, 0])), np.nan) for p in paths
            ]
            self._point_heading = np.concatenate(segment_heading)
        else:
            self._points = np.empty((0, 2))
            self._point_key = np.empty(0)
            self._point_heading = np.empty(0)
        gates = [
            (self._key_base[k] + station + lap * self.length[k], k, crosswalk)
            for k, p in enumerate(spawns)
            for station, crosswalk in p.path.gates
            # A closed path's gate at station g also stands at g + length, one lap on.
            for lap in ((0, 1) if p.path.closed else (0,))
        ]
        gates.sort()
        self._gate_key = np.array([g[0] for g in gates], dtype=np.float64)
        self._gate_owner = np.array([g[1] for g in gates], dtype=np.int64)
        self._gate_crosswalk = np.array([g[2] for g in gates], dtype=np.int64)
        # The same tables as the compiled step takes them.
        self._gate_links = np.stack((self._gate_owner, self._gate_crosswalk)).reshape(2, -1)
        self._path = np.vstack(
            (self._point_key, self._points.T.reshape(2, -1), self._point_heading)
        )
        self._path_bounds = np.stack((self._first, self._last_segment)).astype(np.int64)
        self._search_hints = np.zeros((2, len(spawns)), np.int64)
        """Where each pedestrian's searches of the gates and the path points ended in the
        last compiled step: the next one starts there (they walk on a little a step)."""

    def _place(self, s: FloatArray) -> tuple[FloatArray, FloatArray]:
        key = self._key_base + s
        j = np.searchsorted(self._point_key, key, side="right") - 1
        j = np.clip(j, self._first, self._last_segment)
        span = self._point_key[j + 1] - self._point_key[j]
        t = ((key - self._point_key[j]) / span)[:, None]
        xy = self._points[j] + t * (self._points[j + 1] - self._points[j])
        return xy, self._point_heading[j]

    def stop(self, indices: Indices) -> None:
        """Struck pedestrians stay where they are (or where a contact pushes them)."""
        self.stopped[indices] = True

    def wake(self, points: FloatArray) -> None:
        """Dormant pedestrians whose wake point lies within their active distance of any
        of `points` (K, 2) m (the egos) set off, for good."""
        self.dormant = still_dormant(self.dormant, self.wake_points, self.active_distance, points)

    def shove(self, indices: IntArray, displacement: FloatArray) -> None:
        """A contact's response: push pedestrians `indices` by `displacement` (K, 2) m."""
        self.shoved[indices] += displacement
        self.position[indices] += displacement

    def step(self, dt: float, walk_allowed: BoolArray) -> None:
        """Advance dt s; walk_allowed[c] says whether crosswalk c may be entered now."""
        n = len(self)
        if n == 0:
            return
        if kernels.ACTIVE:
            self.s, self.heading, (self.position, self.velocity, self.acceleration) = (
                pedestrian_motion.walk(
                    dt,
                    self.s,
                    self.stopped,
                    self.dormant,
                    self.walk_speed,
                    walk_allowed,
                    self._key_base,
                    self._gate_key,
                    self._gate_links,
                    self.closed,
                    self.length,
                    self._path,
                    self._path_bounds,
                    self.shoved,
                    self.position,
                    self.velocity,
                    self._search_hints,
                )
            )
            return
        old_s = self.s
        new_s = old_s + np.where(self.stopped | self.dormant, 0.0, self.walk_speed * dt)
        if len(self._gate_key):
            old_key = self._key_base + old_s
            g = np.searchsorted(self._gate_key, old_key, side="left")
            has_gate = g < len(self._gate_key)
            safe = np.where(has_gate, g, 0)
            gate_key = self._gate_key[safe]
            ahead = has_gate & (self._gate_owner[safe] == np.arange(n))
            blocked = (
                ahead
                & (gate_key <= self._key_base + new_s)
                & ~walk_allowed[self._gate_crosswalk[safe]]
            )
            new_s = np.where(blocked, gate_key - self._key_base, new_s)
        new_s = np.where(self.closed & (new_s > self.length), new_s - self.length, new_s)
        self.s = np.minimum(new_s, self.length)
        position, heading = self._place(self.s)
        position += self.shoved
        velocity = (position - self.position) / dt
        self.acceleration = (velocity - self.velocity) / dt
        self.velocity = velocity
        self.position, self.heading = position, heading

    def table(self) -> ObjectTable:
        n = len(self)
        return ObjectTable(
            unique_ids=self.unique_ids,
            object_types=np.full(n, int(ObjectType.PEDESTRIAN), np.int64),
            names=self.names,
            positions=_on_ground(self.position),
            headings=self.heading.copy(),
            velocities=_on_ground(self.velocity),
            accelerations=_on_ground(self.acceleration),
            sizes=self.dims.copy(),
        )


def _on_ground(planar: FloatArray) -> FloatArray:
    """(N, 2) map-frame vectors as (N, 3), z 0."""
    if kernels.ACTIVE:
        spatial: FloatArray = pedestrian_motion.on_ground(planar)
        return spatial
    return np.hstack((planar, np.zeros((len(planar), 1))))


class CrosswalkLights:
    """The lights each crosswalk waits for (see crossed_lights), as one padded table so
    that every crosswalk's walk signal is worked out at once."""

    def __init__(self, crossed: Sequence[tuple[int, ...]]) -> None:
        width = max((len(lights) for lights in crossed), default=0)
        self._lights = np.zeros((len(crossed), width), np.int64)
        self._used = np.zeros((len(crossed), width), bool)
        for k, lights in enumerate(crossed):
            self._lights[k, : len(lights)] = lights
            self._used[k, : len(lights)] = True

    def walk_signals(self, stops_traffic: BoolArray) -> BoolArray:
        """Per crosswalk: True when every light of the road it crosses holds traffic back.

        stops_traffic[l] says light l lets nothing enter now (a plain red); a crosswalk
        over an unsignalised road is always open.
        """
        if self._lights.size == 0:
            return np.ones(len(self._lights), bool)
        walk: BoolArray = np.all(stops_traffic[self._lights] | ~self._used, axis=1)
        return walk


CROSSWALK_SAMPLE_STEP_M = 0.5


def _holding_lights(lane_map: LaneMap, lane_id: str) -> set[str]:
    """The lights that hold the traffic on a lane: its own, or for a junction connector
    those of the lanes leading into it (where a map ends its lanes at the stop line, as
    MGeo does, a crossing at the junction's mouth lies over connectors)."""
    lane = lane_map.lanes[lane_id]
    if lane.traffic_light_ids or not lane.is_junction:
        return set(lane.traffic_light_ids)
    return {light for p in lane.predecessors for light in lane_map.lanes[p].traffic_light_ids}


def crossed_lights(lane_map: LaneMap, light_index: Mapping[str, int]) -> list[tuple[int, ...]]:
    """Per crosswalk (map order): the lights of its junction governing the lanes it lies
    across (the traffic that must be held for it)."""
    result = []
    for crosswalk in lane_map.crosswalks.values():
        start, end = np.array(crosswalk.start), np.array(crosswalk.end)
        count = max(2, int(np.hypot(*(end - start)) / CROSSWALK_SAMPLE_STEP_M) + 1)
        points = start + np.linspace(0.0, 1.0, count)[:, None] * (end - start)
        projection = lane_map.project_many(points)
        inside = np.abs(projection.lateral) <= projection.width / 2.0
        lights = {
            light
            for k in set(projection.lane_index[inside].tolist())
            for light in _holding_lights(lane_map, lane_map.lane_ids[k])
        }
        # A road's lanes away from this junction carry the far junction's light.
        own = [
            i
            for i in lights
            if lane_map.traffic_lights[i].intersection_id == crosswalk.intersection_id
        ]
        result.append(tuple(sorted(light_index[i] for i in own)))
    return result
