"""Poses along lane centrelines (map/lanes.py's LaneMap.poses_at) as a compiled loop."""

from __future__ import annotations

import math

import numpy as np

from egosim.world.arrays import FloatArray, IntArray
from egosim.world.kernels import kernel
from egosim.world.kernels.numpy_scalars import maximum, minimum
from egosim.world.kernels.sorting import search_sorted, search_sorted_near


@kernel
def lane_poses(
    lanes: IntArray,
    s: FloatArray,
    lateral: FloatArray,
    search_hints: IntArray,
    lane_lengths: FloatArray,
    key_base: FloatArray,
    point_key: FloatArray,
    first_point: IntArray,
    last_segment: IntArray,
    point_station: FloatArray,
    points: FloatArray,
    point_heading: FloatArray,
) -> FloatArray:
    """LaneMap.poses_at (N, 4) x, y, z, heading, each point then moved `lateral` m to the
    left of its lane (an empty `lateral`: not moved). search_hints (N,), or empty for
    none: where each point's search of the point keys starts, updated in place."""
    n = lanes.shape[0]
    hinted = search_hints.shape[0] == n
    pose = np.empty((n, 4))
    for i in range(n):
        lane = lanes[i]
        station = minimum(maximum(s[i], 0.0), lane_lengths[lane])
        key = key_base[lane] + station
        if hinted:
            place = search_sorted_near(point_key, key, True, search_hints[i])
            search_hints[i] = place
        else:
            place = search_sorted(point_key, key, True)
        j = place - 1
        j = min(max(j, first_point[lane]), last_segment[lane])
        t = (station - point_station[j]) / (point_station[j + 1] - point_station[j])
        for c in range(points.shape[1]):
            pose[i, c] = points[j, c] + t * (points[j + 1, c] - points[j, c])
        pose[i, 3] = point_heading[j]
    if lateral.shape[0]:
        for i in range(n):
            heading = pose[i, 3]
            pose[i, 0] -= lateral[i] * math.sin(heading)
            pose[i, 1] += lateral[i] * math.cos(heading)
    return pose
