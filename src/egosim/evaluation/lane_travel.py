"""The way along the lane graph between two samples of a drive, however far apart they are.

Between two samples the ego may have moved a few centimetres or tens of metres (a fast car,
a coarse sync step, a sparsely recorded bag): a stop line it passed lies on one of the
lanes of that way, not necessarily on either sample's lane.
"""

from __future__ import annotations

import heapq
from dataclasses import dataclass

from egosim.world.map import Lane, LaneMap

DETOUR_FACTOR = 2.0
"""The way along the lanes may be this much longer than the straight line between the
samples (a turn's arc is at most pi/2 times its chord)."""
DETOUR_ALLOWANCE_M = 2.0
"""... plus this much, for a reference point off its lanes' centre lines."""


@dataclass(frozen=True)
class Stretch:
    """The part [start_s, end_s] of one lane the ego drove along, `before_m` metres into
    the way (the distance driven from the first sample to this stretch's start)."""

    lane_id: str
    start_s: float
    end_s: float
    before_m: float


@dataclass(frozen=True)
class Way:
    stretches: tuple[Stretch, ...]
    length_m: float

    def fraction_at(self, stretch: Stretch, s: float) -> float:
        """How far along the way station `s` of `stretch` lies, 0..1."""
        if self.length_m <= 0.0:
            return 1.0
        return (stretch.before_m + s - stretch.start_s) / self.length_m


def way_between(
    lane_map: LaneMap, start: tuple[str, float], end: tuple[str, float], chord_m: float
) -> Way | None:
    """The shortest way from (lane, s) `start` to `end` forward along the lanes, their
    successors and lane-change neighbours, if one is no longer than the straight line
    between the two points (`chord_m`) allows; None when there is none (the ego went
    backwards, was moved, or left the lanes)."""
    limit = DETOUR_FACTOR * chord_m + DETOUR_ALLOWANCE_M
    end_lane, end_s = end
    best: Way | None = None
    # Entries: (distance to the end of the lane, tie-breaker, lane, stretches up to it).
    queue: list[tuple[float, int, Lane, tuple[Stretch, ...]]] = []
    for k, (lane, s) in enumerate(_beside(lane_map, *start)):
        if lane.id == end_lane and end_s >= s:
            best = _shorter(best, Way((Stretch(lane.id, s, end_s, 0.0),), end_s - s))
        queue.append((lane.length - s, k, lane, (Stretch(lane.id, s, lane.length, 0.0),)))
    heapq.heapify(queue)
    tie = len(queue)
    done: set[str] = set()
    while queue:
        reached, _, lane, stretches = heapq.heappop(queue)
        if reached > limit or (best is not None and reached >= best.length_m):
            break
        if lane.id in done:
            continue
        done.add(lane.id)
        for successor_id in lane.successors:
            successor = lane_map.lanes[successor_id]
            if successor_id == end_lane:
                stretch = Stretch(successor_id, 0.0, end_s, reached)
                best = _shorter(best, Way((*stretches, stretch), reached + end_s))
            if successor_id not in done:
                tie += 1
                stretch = Stretch(successor_id, 0.0, successor.length, reached)
                entry = (reached + successor.length, tie, successor, (*stretches, stretch))
                heapq.heappush(queue, entry)
    return best if best is not None and best.length_m <= limit else None


def _beside(lane_map: LaneMap, lane_id: str, s: float) -> list[tuple[Lane, float]]:
    """The lane at station s and every lane-change neighbour beside it, at the same share
    of its length (lanes side by side run alike)."""
    lane = lane_map.lanes[lane_id]
    found = [(lane, s)]
    for side in ("left_neighbor", "right_neighbor"):
        other_id = getattr(lane, side)
        while other_id is not None and all(other_id != seen.id for seen, _ in found):
            other = lane_map.lanes[other_id]
            found.append((other, s * other.length / lane.length))
            other_id = getattr(other, side)
    return found


def _shorter(known: Way | None, way: Way) -> Way:
    return way if known is None or way.length_m < known.length_m else known
