"""Which head a vehicle should be looking at (GetTrafficLightStatus's "closest light")."""

from __future__ import annotations

import math
from collections.abc import Iterable

from egosim.world.map import LaneMap

DEFAULT_LOOKAHEAD_M = 300.0
"""How far down the lane graph the governing light is looked for, m."""


def governing_light_id(
    lane_map: LaneMap,
    lane_id: str,
    s: float,
    x: float,
    y: float,
    lookahead_m: float = DEFAULT_LOOKAHEAD_M,
) -> str | None:
    """The head governing the stop line next ahead of (lane_id, s) that stands nearest to
    (x, y), else the nearest light of the map to (x, y).

    Ahead means on this lane before its stop line, or on the lanes that follow within
    `lookahead_m` (taking each lane's first successor). Where several heads govern that
    stop line, the nearest one is the one MORAI SIM reports (a K-City stop line has a
    round-green head and a left-arrow head 3 m apart). None when the map has no lights.
    """
    lane = lane_map.lane(lane_id)
    travelled = -s
    seen: set[str] = set()
    while travelled <= lookahead_m and lane.id not in seen:
        seen.add(lane.id)
        if lane.traffic_light_ids:
            stop = lane.length if lane.stop_line_s is None else lane.stop_line_s
            if travelled + stop >= 0.0:
                return nearest_light_id(lane_map, x, y, lane.traffic_light_ids)
        if not lane.successors:
            break
        travelled += lane.length
        lane = lane_map.lanes[lane.successors[0]]
    return nearest_light_id(lane_map, x, y)


def nearest_light_id(
    lane_map: LaneMap, x: float, y: float, among: Iterable[str] | None = None
) -> str | None:
    """The light standing closest to (x, y) in the plane, of `among` (default: all the
    map's lights; ties go to the first); None when there are none."""
    best, best_distance = None, math.inf
    for light_id in lane_map.traffic_lights if among is None else among:
        site = lane_map.traffic_lights[light_id]
        distance = math.hypot(site.position[0] - x, site.position[1] - y)
        if distance < best_distance:
            best, best_distance = site.id, distance
    return best
