"""Road coordinates over a LaneMap: OpenSCENARIO's (road id, lane id, s, t) and back.

A map built from OpenDRIVE keeps its roads (world/map/opendrive/road_frame.py): road
`s` runs along the road's reference line, `t` to its left, and lane ids are OpenDRIVE's
(negative right of the reference line, positive left). A map without roads (MGeo, the
built-in maps) gets `LaneRoads`: every lane is a road of one lane, id -1, whose
reference line is the lane's centreline, so a LanePosition names a lane (MGeo link) by
its id.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import numpy as np
import numpy.typing as npt


class UnknownRoadError(LookupError):
    """A road, lane or station the map does not have; the message says which."""


@dataclass(frozen=True)
class RoadPoint:
    """A place in road coordinates: station s (m) along road `road` from its start, `t`
    (m) left of its reference line, on OpenDRIVE lane `lane` there."""

    road: str
    lane: int
    s: float
    t: float


@dataclass(frozen=True)
class LanePlace:
    """The egosim lane (index) and station (m) of a road position, and the position's
    offset (m, left of the lane's travel direction) from that lane's centreline."""

    lane_index: int
    station: float
    offset: float


class RoadCoordinates(Protocol):
    """What OpenSCENARIO positions need of a map's roads."""

    def road_ids(self) -> tuple[str, ...]: ...

    def road_length(self, road: str) -> float: ...

    def pose(self, road: str, s: float, t: float) -> tuple[float, float, float, float]:
        """x, y, z and the reference line's heading (rad) at (s, t)."""
        ...

    def lane_centre_t(self, road: str, lane: int, s: float) -> float:
        """t of OpenDRIVE lane `lane`'s centreline at s (UnknownRoadError if none there)."""
        ...

    def lane_place(self, road: str, lane: int, s: float, offset: float) -> LanePlace:
        """The egosim lane holding (road, lane) at s; `offset` is along +t."""
        ...

    def locate(self, lane_index: int, station: float, offset: float) -> RoadPoint:
        """Road coordinates of the point `offset` m left of egosim lane `lane_index` at
        `station`."""
        ...

    def forward(self, lane_index: int) -> bool:
        """The egosim lane travels along +s of its road."""
        ...


def interpolate(x: float, xs: npt.NDArray[np.float64], ys: npt.NDArray[np.float64]) -> float:
    """ys at x over an increasing or decreasing xs, clamped at the ends."""
    if xs[0] > xs[-1]:
        return float(np.interp(x, xs[::-1], ys[::-1]))
    return float(np.interp(x, xs, ys))
