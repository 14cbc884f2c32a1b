"""The roads of an OpenDRIVE map as road coordinates (egosim.world.map.road_coordinates):
positions in (road, lane, s, t) placed on the map, and the map's lanes read back in them."""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from egosim.world.arrays import FloatArray
from egosim.world.map.lanes import LaneMap
from egosim.world.map.opendrive.document import Road
from egosim.world.map.opendrive.reference_line import lateral_points, reference_poses
from egosim.world.map.opendrive.road_lanes import (
    LaneKey,
    RoadLane,
    lane_id,
    lateral_layout,
    section_range,
)
from egosim.world.map.road_coordinates import (
    LanePlace,
    RoadPoint,
    UnknownRoadError,
    interpolate,
)


class OpenDriveRoads:
    """Road coordinates of an OpenDRIVE document's roads over the LaneMap built from it."""

    def __init__(
        self, roads: Mapping[str, Road], lanes: Mapping[LaneKey, RoadLane], lane_map: LaneMap
    ) -> None:
        self._roads = dict(roads)
        self._lane_map = lane_map
        self._by_index: dict[int, RoadLane] = {}
        for lane in lanes.values():
            if lane.id in lane_map.lanes:
                self._by_index[lane_map.lane_index(lane.id)] = lane
        self._stations: dict[int, FloatArray] = {
            index: lane_map.lanes[lane.id].stations for index, lane in self._by_index.items()
        }

    def road_ids(self) -> tuple[str, ...]:
        return tuple(self._roads)

    def _road(self, road: str) -> Road:
        try:
            return self._roads[road]
        except KeyError:
            raise UnknownRoadError(f"no road {road!r} in the OpenDRIVE map") from None

    def road_length(self, road: str) -> float:
        return self._road(road).length

    def pose(self, road: str, s: float, t: float) -> tuple[float, float, float, float]:
        record = self._road(road)
        poses = reference_poses(record, np.array([s]))
        x, y = lateral_points(poses, [t])[0]
        return float(x), float(y), float(poses[0, 2]), float(poses[0, 3])

    def _section(self, record: Road, s: float) -> int:
        starts = [section.s for section in record.sections]
        return max(int(np.searchsorted(starts, s + 1e-9, side="right")) - 1, 0)

    def lane_centre_t(self, road: str, lane: int, s: float) -> float:
        record = self._road(road)
        k = self._section(record, s)
        start, _ = section_range(record, k)
        stations = np.array([min(max(s, 0.0), record.length)])
        centres, _ = lateral_layout(
            record, record.sections[k].lanes, stations - start, stations, []
        )
        if lane not in centres:
            raise UnknownRoadError(f"road {road!r} has no lane {lane} at s={s:g}")
        return float(centres[lane][0])

    def lane_place(self, road: str, lane: int, s: float, offset: float) -> LanePlace:
        record = self._road(road)
        key = lane_id(LaneKey(road, self._section(record, s), lane))
        if key not in self._lane_map.lanes:
            raise UnknownRoadError(f"road {road!r} has no drivable lane {lane} at s={s:g}")
        index = self._lane_map.lane_index(key)
        road_lane = self._by_index[index]
        station = interpolate(s, road_lane.road_s, self._stations[index])
        return LanePlace(index, station, offset if road_lane.forward else -offset)

    def locate(self, lane_index: int, station: float, offset: float) -> RoadPoint:
        road_lane = self._by_index.get(lane_index)
        if road_lane is None:
            lane = self._lane_map.lane_ids[lane_index]
            raise UnknownRoadError(f"lane {lane!r} belongs to no OpenDRIVE road")
        s = interpolate(station, self._stations[lane_index], road_lane.road_s)
        key = road_lane.key
        centre = self.lane_centre_t(key.road, key.lane, s)
        return RoadPoint(key.road, key.lane, s, centre + (offset if road_lane.forward else -offset))

    def forward(self, lane_index: int) -> bool:
        road_lane = self._by_index.get(lane_index)
        return True if road_lane is None else road_lane.forward
