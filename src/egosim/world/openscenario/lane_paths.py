"""Moving along the lane graph: an entity's next lane at a fork, a station advanced
over lane ends, and distances along lanes between two places."""

from __future__ import annotations

import math
from collections.abc import Sequence

from egosim.world.map import LaneMap
from egosim.world.map.polyline import segment_headings

SEARCH_LANES = 6
"""Lanes searched ahead and behind for a distance along lanes."""


def _turn(lane_map: LaneMap, lane_id: str) -> float:
    headings = segment_headings(lane_map.lanes[lane_id].centerline)
    return abs(math.remainder(float(headings[-1] - headings[0]), math.tau))


def next_lane(
    lane_map: LaneMap, lane: int, route: Sequence[int] = (), route_position: int = 0
) -> tuple[int, int]:
    """(successor lane index, new route position): the route's next lane where it names
    a successor, else the straightest successor; -1 at a dead end."""
    successors = lane_map.lanes[lane_map.lane_ids[lane]].successors
    if not successors:
        return -1, route_position
    indices = [lane_map.lane_index(s) for s in successors]
    for k in range(route_position, len(route)):
        if route[k] in indices:
            return route[k], k + 1
    straightest = min(successors, key=lambda s: _turn(lane_map, s))
    return lane_map.lane_index(straightest), route_position


def previous_lane(lane_map: LaneMap, lane: int) -> int:
    predecessors = lane_map.lanes[lane_map.lane_ids[lane]].predecessors
    if not predecessors:
        return -1
    return lane_map.lane_index(min(predecessors, key=lambda p: _turn(lane_map, p)))


def advance(
    lane_map: LaneMap,
    lane: int,
    station: float,
    distance: float,
    route: Sequence[int] = (),
    route_position: int = 0,
) -> tuple[int, float, int, bool]:
    """(lane, station, route position, at a lane end) after moving `distance` m along
    the lanes (negative: backwards, onto predecessors): stopped at one in this step, or
    standing at the end of a lane with no successor."""
    station += distance
    lengths = lane_map.lane_lengths
    while station > lengths[lane]:
        following, route_position = next_lane(lane_map, lane, route, route_position)
        if following < 0:
            return lane, float(lengths[lane]), route_position, True
        station -= float(lengths[lane])
        lane = following
    while station < 0.0:
        before = previous_lane(lane_map, lane)
        if before < 0:
            return lane, 0.0, route_position, True
        lane = before
        station += float(lengths[lane])
    # An entity that stopped at a dead end in an earlier step is still at it.
    at_dead_end = (
        distance >= 0.0
        and station >= lengths[lane]
        and not lane_map.lanes[lane_map.lane_ids[lane]].successors
    )
    return lane, station, route_position, at_dead_end


def distance_along(
    lane_map: LaneMap, from_lane: int, from_station: float, to_lane: int, to_station: float
) -> float | None:
    """Signed distance (m) along lanes from one place to another (positive: the second
    lies ahead in travel direction), searching SEARCH_LANES lanes each way along the
    straightest successors and predecessors; None when neither search meets it."""
    if from_lane == to_lane:
        return to_station - from_station
    lengths = lane_map.lane_lengths
    lane, covered = from_lane, float(lengths[from_lane]) - from_station
    for _ in range(SEARCH_LANES):
        successors = [
            lane_map.lane_index(s) for s in lane_map.lanes[lane_map.lane_ids[lane]].successors
        ]
        if to_lane in successors:
            return covered + to_station
        lane, _ = next_lane(lane_map, lane)
        if lane < 0:
            break
        covered += float(lengths[lane])
    lane, covered = from_lane, from_station
    for _ in range(SEARCH_LANES):
        predecessors = [
            lane_map.lane_index(p) for p in lane_map.lanes[lane_map.lane_ids[lane]].predecessors
        ]
        if to_lane in predecessors:
            return -(covered + float(lengths[to_lane]) - to_station)
        lane = previous_lane(lane_map, lane)
        if lane < 0:
            break
        covered += float(lengths[lane])
    return None
