"""Road coordinates for maps without roads of their own (MGeo, the built-in maps)."""

from __future__ import annotations

import math

from egosim.world.map.lanes import LaneMap
from egosim.world.map.road_coordinates import (
    LanePlace,
    RoadCoordinates,
    RoadPoint,
    UnknownRoadError,
)


class LaneRoads:
    """Road coordinates for a map without roads: each lane is road `lane id`, lane -1."""

    def __init__(self, lane_map: LaneMap) -> None:
        self.lane_map = lane_map

    def road_ids(self) -> tuple[str, ...]:
        return self.lane_map.lane_ids

    def _index(self, road: str) -> int:
        if road not in self.lane_map.lanes:
            raise UnknownRoadError(f"no road (lane) {road!r} in map {self.lane_map.name!r}")
        return self.lane_map.lane_index(road)

    def road_length(self, road: str) -> float:
        return float(self.lane_map.lane_lengths[self._index(road)])

    def pose(self, road: str, s: float, t: float) -> tuple[float, float, float, float]:
        x, y, z, heading = self.lane_map.poses_at([self._index(road)], [s])[0]
        return (
            float(x - t * math.sin(heading)),
            float(y + t * math.cos(heading)),
            float(z),
            float(heading),
        )

    def lane_centre_t(self, road: str, lane: int, s: float) -> float:
        self._index(road)
        return 0.0

    def lane_place(self, road: str, lane: int, s: float, offset: float) -> LanePlace:
        return LanePlace(self._index(road), s, offset)

    def locate(self, lane_index: int, station: float, offset: float) -> RoadPoint:
        return RoadPoint(self.lane_map.lane_ids[lane_index], -1, station, offset)

    def forward(self, lane_index: int) -> bool:
        return True


def road_coordinates_of(lane_map: LaneMap) -> RoadCoordinates:
    """The map's own roads where it has them (OpenDRIVE), else LaneRoads."""
    roads = lane_map.roads
    return LaneRoads(lane_map) if roads is None else roads
