"""Which light a vehicle should be looking at (GetTrafficLightStatus's "closest light")."""

from __future__ import annotations

import math

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
    """The light whose stop line is next ahead of (lane_id, s), else the nearest light to (x, y).

    Ahead means on this lane before its stop line, or on the lanes that follow within
    `lookahead_m` (taking each lane's first successor). None when the map has no lights.
    """
    lane = lane_map.lane(lane_id)
    travelled = -s
    seen: set[str] = set()
    while travelled <= lookahead_m and lane.id not in seen:
        seen.add(lane.id)
        if lane.traffic_light_id is not None:
            stop = lane.length if lane.stop_line_s is None else lane.stop_line_s
            if travelled + stop >= 0.0:
                return lane.traffic_light_id
        if not lane.successors:
            break
        travelled += lane.length
        lane = lane_map.lanes[lane.successors[0]]
    return nearest_light_id(lane_map, x, y)


def nearest_light_id(lane_map: LaneMap, x: float, y: float) -> str | None:
    """The light standing closest to (x, y) in the plane; None when there are none."""
    best, best_distance = None, math.inf
    for site in lane_map.traffic_lights.values():
        distance = math.hypot(site.position[0] - x, site.position[1] - y)
        if distance < best_distance:
            best, best_distance = site.id, distance
    return best
