"""A route the ego should drive, and how much of it it has driven."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

from egosim.evaluation.lane_travel import DETOUR_FACTOR
from egosim.world.arrays import FloatArray
from egosim.world.map import LaneMap

ROUTE_TOLERANCE_M = 4.0
"""Farther than this from the route, the ego's position does not count as progress."""
SEARCH_BEHIND_M = 5.0
SEARCH_AHEAD_M = 25.0
"""Progress is looked for in this window around the progress so far, so a route that
passes the same place twice (a lap) is followed in order."""
COMPLETE_WITHIN_M = 1.0
"""A route counts as completed once the progress is this close to its end."""


class RouteError(ValueError):
    """A route that cannot be built (too few points, unknown lanes)."""


class Route:
    """A polyline in the map frame (m) with arc-length stations."""

    def __init__(self, points: npt.ArrayLike) -> None:
        xy = np.asarray(points, dtype=np.float64).reshape(-1, 2)
        keep = np.concatenate(([True], np.hypot(*np.diff(xy, axis=0).T) > 1e-9))
        xy = xy[keep]
        if len(xy) < 2:
            raise RouteError("a route needs at least two distinct points")
        self.points: FloatArray = xy
        self.stations: FloatArray = np.concatenate(
            ([0.0], np.cumsum(np.hypot(*np.diff(xy, axis=0).T)))
        )
        self.length = float(self.stations[-1])

    @classmethod
    def through_lanes(cls, lane_map: LaneMap, lane_ids: Sequence[str]) -> Route:
        """The centrelines of `lane_ids`, one after the other."""
        unknown = [lane_id for lane_id in lane_ids if lane_id not in lane_map.lanes]
        if unknown:
            raise RouteError(f"no lane {unknown[0]!r} in map {lane_map.name!r}")
        return cls(np.concatenate([lane_map.lanes[i].centerline[:, :2] for i in lane_ids]))

    def first(self, length_m: float) -> Route:
        """The route's first `length_m` metres (all of it if shorter)."""
        if length_m >= self.length:
            return self
        end = int(np.searchsorted(self.stations, length_m, side="right"))
        k = end - 1
        fraction = (length_m - self.stations[k]) / (self.stations[k + 1] - self.stations[k])
        cut = self.points[k] + fraction * (self.points[k + 1] - self.points[k])
        return Route(np.vstack((self.points[:end], cut)))

    def locate(self, x: float, y: float, low_s: float, high_s: float) -> tuple[float, float]:
        """(station, distance) of the point of the route between stations low_s and high_s
        nearest to (x, y)."""
        first = max(int(np.searchsorted(self.stations, low_s, side="right")) - 1, 0)
        last = min(int(np.searchsorted(self.stations, high_s, side="left")), len(self.points) - 1)
        start, end = self.points[first:last], self.points[first + 1 : last + 1]
        seg = end - start
        seg_len2 = np.maximum(np.sum(seg * seg, axis=1), 1e-18)
        t = np.clip(np.sum((np.array([x, y]) - start) * seg, axis=1) / seg_len2, 0.0, 1.0)
        nearest = start + t[:, None] * seg
        distance = np.hypot(nearest[:, 0] - x, nearest[:, 1] - y)
        k = int(np.argmin(distance))
        s = self.stations[first + k] + t[k] * np.sqrt(seg_len2[k])
        return float(s), float(distance[k])


class RouteProgress:
    """The farthest station of the route reached so far, followed in order."""

    def __init__(self, route: Route) -> None:
        self.route = route
        self.progress_m = 0.0
        self._last: tuple[float, float] | None = None

    def update(self, x: float, y: float) -> None:
        # Samples far apart (a fast car, a long sync tick) move the ego further than the
        # window: it reaches as far ahead as the ego can have driven since the last one.
        moved = 0.0 if self._last is None else math.hypot(x - self._last[0], y - self._last[1])
        self._last = (x, y)
        ahead = SEARCH_AHEAD_M + DETOUR_FACTOR * moved
        s, distance = self.route.locate(
            x, y, self.progress_m - SEARCH_BEHIND_M, self.progress_m + ahead
        )
        if distance <= ROUTE_TOLERANCE_M:
            self.progress_m = max(self.progress_m, s)

    @property
    def completion(self) -> float:
        """Fraction of the route driven, 0..1."""
        if self.completed:
            return 1.0
        return min(self.progress_m / self.route.length, 1.0)

    @property
    def completed(self) -> bool:
        return self.progress_m >= self.route.length - COMPLETE_WITHIN_M
