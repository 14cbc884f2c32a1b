"""Right of way inside junctions, beyond what the lights give.

Two rules keep NPCs from meeting inside a junction box:
- yield: a vehicle enters a junction lane only if no lane crossing or merging with it is
  occupied, or claimed this step by a vehicle nearer its own entry (this is what runs
  junctions whose lights flash or are dark, and clears vehicles left in the box when the
  phase changes);
- keep the box clear: a vehicle enters only if its exit lane has room for it.
Both only stop vehicles that can still stop comfortably before the junction.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np
import numpy.typing as npt

from egosim.world.arrays import FloatArray, IntArray
from egosim.world.map import LaneMap

CONFLICT_DISTANCE_M = 2.5
"""Junction lanes whose centrelines come closer than this cross or merge: two cars on
them would touch."""
DECISION_MARGIN_M = 5.0
"""Vehicles decide at their comfortable stopping distance from the junction plus this."""


@lru_cache(maxsize=8)
def junction_conflicts(lane_map: LaneMap) -> IntArray:
    """(L, K) per lane, the junction lanes it conflicts with (padded with -1).

    Lanes leaving the same lane do not conflict: they share their start, and the vehicles
    on them already follow one another there.
    """
    lanes = [lane_map.lanes[i] for i in lane_map.lane_ids]
    junction = [k for k, lane in enumerate(lanes) if lane.is_junction]
    points = [lanes[k].centerline[:, :2] for k in junction]
    low = np.array([p.min(axis=0) for p in points]).reshape(-1, 2) - CONFLICT_DISTANCE_M
    high = np.array([p.max(axis=0) for p in points]).reshape(-1, 2) + CONFLICT_DISTANCE_M
    found: list[list[int]] = [[] for _ in lanes]
    for a in range(len(junction)):
        near = np.flatnonzero(
            np.all(low[a + 1 :] <= high[a], axis=1) & np.all(low[a] <= high[a + 1 :], axis=1)
        )
        for b in near + a + 1:
            la, lb = lanes[junction[a]], lanes[junction[b]]
            if set(la.predecessors) & set(lb.predecessors):
                continue
            gaps = points[a][:, None, :] - points[b][None, :, :]
            if np.min(np.einsum("ijk,ijk->ij", gaps, gaps)) < CONFLICT_DISTANCE_M**2:
                found[junction[a]].append(junction[b])
                found[junction[b]].append(junction[a])
    width = max(1, *(len(f) for f in found))
    table = np.full((len(lanes), width), -1, dtype=np.int64)
    for k, row in enumerate(found):
        table[k, : len(row)] = row
    return table


def junction_entry_gap(
    conflicts: IntArray,
    is_junction: npt.NDArray[np.bool_],
    entry_distance: FloatArray,
    entering: IntArray,
    exit_room: FloatArray,
    needed_room: FloatArray,
    stoppable: npt.NDArray[np.bool_],
    occupied: npt.NDArray[np.bool_],
    decision_distance: FloatArray,
) -> FloatArray:
    """Per vehicle, the distance (m) to the junction entry where it must wait, else inf.

    entry_distance: bumper to the end of the current lane; entering: the junction lane
    it takes next (-1: none); exit_room / needed_room: free length on the lane after it and
    the length the vehicle needs there; occupied: per lane, someone is on it.
    """
    n = len(entering)
    gap = np.full(n, np.inf)
    approaching = (entering >= 0) & (entry_distance <= decision_distance)
    approaching[approaching] = is_junction[entering[approaching]]
    rows = np.flatnonzero(approaching)
    if rows.size == 0:
        return gap
    lane_conflicts = conflicts[entering[rows]]
    padded_occupied = np.append(occupied, False)
    blocked = padded_occupied[lane_conflicts].any(axis=1) | (exit_room[rows] < needed_room[rows])
    claimed = np.zeros(len(occupied) + 1, dtype=bool)
    # Nearest first (index order on ties): who claims a lane first keeps it this step.
    for k in np.lexsort((rows, entry_distance[rows])):
        must_wait = blocked[k] or claimed[lane_conflicts[k]].any()
        if must_wait and stoppable[rows[k]]:
            gap[rows[k]] = entry_distance[rows[k]]
            continue
        claimed[entering[rows[k]]] = True
    return gap
