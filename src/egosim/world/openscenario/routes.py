"""Routes: waypoints laid on the lane graph as the lanes an entity takes.

Between two waypoints the route is the shortest chain of lanes (successors, and lane
changes to a lane beside at a small cost) from the first waypoint's lane to the
second's; `routeStrategy` is read but every strategy takes that chain.
"""

from __future__ import annotations

import heapq
import itertools
from dataclasses import dataclass, field

from egosim.world.openscenario.positions import (
    Position,
    PositionError,
    RouteLanes,
    attach,
)
from egosim.world.openscenario.runtime import Runtime
from egosim.world.openscenario.xmltree import Node

LANE_CHANGE_COST_M = 20.0


@dataclass(frozen=True)
class Route:
    node: Node
    name: str
    closed: bool
    waypoints: tuple[Position, ...]
    _cache: dict[str, RouteLanes] = field(default_factory=dict, compare=False, repr=False)

    def lanes(self, rt: Runtime) -> RouteLanes:
        known = self._cache.get("lanes")
        if known is not None:
            return known
        places = []
        for waypoint in self.waypoints:
            placement = waypoint.resolve(rt)
            lane = placement.lane or attach(rt, placement)
            if lane is None:
                raise PositionError(f"route {self.name!r}: a waypoint lies on no lane")
            places.append(lane)
        chain = [places[0].lane_index]
        for a, b in itertools.pairwise(places):
            chain += shortest_lanes(rt, a.lane_index, b.lane_index)[1:]
        lanes = RouteLanes(tuple(chain), places[0].station)
        self._cache["lanes"] = lanes
        return lanes


def shortest_lanes(rt: Runtime, start: int, goal: int) -> list[int]:
    """Lane indices from `start` to `goal` (both included) along successors and
    neighbours; PositionError when the goal cannot be reached."""
    lane_map = rt.lane_map
    lengths = lane_map.lane_lengths
    best = {start: 0.0}
    before: dict[int, int] = {}
    queue = [(0.0, start)]
    while queue:
        cost, lane = heapq.heappop(queue)
        if lane == goal:
            chain = [goal]
            while chain[-1] != start:
                chain.append(before[chain[-1]])
            return chain[::-1]
        if cost > best.get(lane, float("inf")):
            continue
        record = lane_map.lanes[lane_map.lane_ids[lane]]
        steps = [(lane_map.lane_index(s), float(lengths[lane])) for s in record.successors]
        steps += [
            (lane_map.lane_index(n), LANE_CHANGE_COST_M)
            for n in (record.left_neighbor, record.right_neighbor)
            if n is not None
        ]
        for following, step in steps:
            total = cost + step
            if total < best.get(following, float("inf")):
                best[following] = total
                before[following] = lane
                heapq.heappush(queue, (total, following))
    raise PositionError(
        f"no way along the lanes from {lane_map.lane_ids[start]} to {lane_map.lane_ids[goal]}"
    )
