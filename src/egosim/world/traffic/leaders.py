"""Who is ahead of whom along the lane graph: the leader search behind car following."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from egosim.world.arrays import FloatArray, IntArray
from egosim.world.traffic.lane_graph import LaneGraph


@dataclass(frozen=True, eq=False)
class LaneOccupants:
    """Road users placed on lanes: lane index, station of their centre (m), half their
    length (m) and speed along the lane (m/s)."""

    lane: IntArray
    s: FloatArray
    half_length: FloatArray
    speed: FloatArray

    @classmethod
    def empty(cls) -> LaneOccupants:
        """No occupants (one shared value: arrays of no elements cannot change)."""
        return _NOBODY

    @classmethod
    def concatenate(cls, parts: list[LaneOccupants]) -> LaneOccupants:
        """The occupants of `parts` one after the other, in new arrays (most parts of a
        step are empty: they are left out of the joining)."""
        filled = [p for p in parts if len(p.lane)] or parts[:1]
        if not filled:
            return cls.empty()
        return cls(
            np.concatenate([p.lane for p in filled]),
            np.concatenate([p.s for p in filled]),
            np.concatenate([p.half_length for p in filled]),
            np.concatenate([p.speed for p in filled]),
        )


_NOBODY = LaneOccupants(np.empty(0, np.int64), np.empty(0), np.empty(0), np.empty(0))


def leaders_ahead(
    graph: LaneGraph,
    occupants: LaneOccupants,
    follower_slots: IntArray,
    next_lanes: IntArray,
) -> tuple[FloatArray, IntArray]:
    """For each follower (an index into occupants) the nearest occupant ahead.

    Ahead is further along the follower's lane, else the first occupant of its next lane,
    else of the lane after (next_lanes is (n, 2), -1 where the path ends). Returns the
    centre-to-centre distance along the path (inf if none) and the leader's slot (-1).
    """
    m = len(occupants.lane)
    order = np.lexsort((occupants.s, occupants.lane))
    sorted_lane = occupants.lane[order]
    sorted_s = occupants.s[order]
    rank = np.empty(m, dtype=np.int64)
    rank[order] = np.arange(m)

    lane = occupants.lane[follower_slots]
    s = occupants.s[follower_slots]
    distance = np.full(len(follower_slots), np.inf)
    leader = np.full(len(follower_slots), -1, dtype=np.int64)

    behind = rank[follower_slots] + 1
    on_lane = behind < m
    on_lane[on_lane] = sorted_lane[behind[on_lane]] == lane[on_lane]
    distance[on_lane] = sorted_s[behind[on_lane]] - s[on_lane]
    leader[on_lane] = order[behind[on_lane]]

    offset = graph.length[lane] - s
    for k in range(next_lanes.shape[1]):
        target = next_lanes[:, k]
        pending = (leader < 0) & (target >= 0)
        first = np.searchsorted(sorted_lane, target[pending], side="left")
        found = first < m
        found[found] = sorted_lane[first[found]] == target[pending][found]
        rows = np.flatnonzero(pending)[found]
        candidate = order[first[found]]
        # On a ring shorter than the look-ahead a follower would meet itself.
        other = candidate != follower_slots[rows]
        rows, candidate = rows[other], candidate[other]
        distance[rows] = offset[rows] + occupants.s[candidate]
        leader[rows] = candidate
        safe_target = np.where(target >= 0, target, 0)
        offset = offset + np.where(target >= 0, graph.length[safe_target], np.inf)
    return distance, leader
