"""The pedestrians' step (traffic/pedestrians.py's PedestrianCrowd.step) as one compiled
loop: walking, waiting at crosswalk gates, and the path pose that follows."""

from __future__ import annotations

import numpy as np

from egosim.world.arrays import BoolArray, FloatArray, IntArray
from egosim.world.kernels import kernel
from egosim.world.kernels.numpy_scalars import minimum
from egosim.world.kernels.sorting import search_sorted_near


@kernel
def walk(
    dt: float,
    s: FloatArray,
    stopped: BoolArray,
    dormant: BoolArray,
    walk_speed: FloatArray,
    walk_allowed: BoolArray,
    key_base: FloatArray,
    gates: FloatArray,
    gate_links: IntArray,
    closed: BoolArray,
    length: FloatArray,
    path: FloatArray,
    first_last: IntArray,
    shoved: FloatArray,
    position: FloatArray,
    velocity: FloatArray,
    search_hints: IntArray,
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """New stations, headings and (3, N, 2) positions, velocities and accelerations.

    gates: each gate's key; gate_links rows: its owner, its crosswalk. path rows: point
    key, x, y, heading of the segment from it; first_last rows: each path's first point
    and last segment. search_hints rows: where each pedestrian's search of the gates and
    of the path points ended last time (any values will do: the searches start there),
    updated in place.
    """
    n = s.shape[0]
    new_station = np.empty(n)
    heading = np.empty(n)
    motion = np.empty((3, n, 2))
    point_key = path[0]
    for i in range(n):
        new_s = s[i] + (0.0 if stopped[i] or dormant[i] else walk_speed[i] * dt)
        if gates.shape[0]:
            g = search_sorted_near(gates, key_base[i] + s[i], False, search_hints[0, i])
            search_hints[0, i] = g
            safe = g if g < gates.shape[0] else 0
            if (
                g < gates.shape[0]
                and gate_links[0, safe] == i
                and gates[safe] <= key_base[i] + new_s
                and not walk_allowed[gate_links[1, safe]]
            ):
                new_s = gates[safe] - key_base[i]
        if closed[i] and new_s > length[i]:
            new_s = new_s - length[i]
        station = minimum(new_s, length[i])
        new_station[i] = station
        key = key_base[i] + station
        place = search_sorted_near(point_key, key, True, search_hints[1, i])
        search_hints[1, i] = place
        j = place - 1
        j = min(max(j, first_last[0, i]), first_last[1, i])
        t = (key - point_key[j]) / (point_key[j + 1] - point_key[j])
        for d in range(2):
            at = path[1 + d, j] + t * (path[1 + d, j + 1] - path[1 + d, j]) + shoved[i, d]
            speed = (at - position[i, d]) / dt
            motion[0, i, d] = at
            motion[1, i, d] = speed
            motion[2, i, d] = (speed - velocity[i, d]) / dt
        heading[i] = path[3, j]
    return new_station, heading, motion


@kernel
def on_ground(planar: FloatArray) -> FloatArray:
    """np.hstack((planar, zeros)): (N, 2) map-frame vectors as (N, 3)."""
    n = planar.shape[0]
    spatial = np.empty((n, 3))
    for i in range(n):
        spatial[i, 0], spatial[i, 1], spatial[i, 2] = planar[i, 0], planar[i, 1], 0.0
    return spatial
