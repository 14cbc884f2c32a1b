"""Lines across a lane: where its edges are at a station (stop lines, drawn or rendered)."""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

from egosim.world.map.lanes import LaneMap


def lane_cross_section(lane_map: LaneMap, lane_id: str, s: float) -> npt.NDArray[np.float64]:
    """(2, 3): the lane's left and right edge at station `s` (clamped), square to the
    centre line there, at the centre line's height."""
    lane = lane_map.lane(lane_id)
    x, y, z, heading = lane_map.pose_at(lane_id, s)
    half = float(np.interp(s, lane.stations, lane.widths)) / 2.0
    left = np.array((-math.sin(heading), math.cos(heading), 0.0)) * half
    centre = np.array((x, y, z))
    return np.array((centre + left, centre - left))
