"""Placing objects on lanes, for agents that react to whoever stands there.

Each kind of object has its own rule for when it stands in a lane (the `*_on_lanes`
functions), given where the lane projection placed it.
"""

from __future__ import annotations

import numpy as np

from egosim.world.map import LaneMap, LaneProjections
from egosim.world.traffic.leaders import LaneOccupants
from egosim.world.traffic.objects import ObjectTable

PEDESTRIAN_LANE_MARGIN_M = 1.0
"""A pedestrian this close to a lane's edge already counts as in the lane for drivers."""
PEDESTRIAN_HALF_DEPTH_M = 0.5


def lane_occupants_of(
    table: ObjectTable, lane_map: LaneMap, but: int | None = None
) -> LaneOccupants:
    """The vehicles of `table` (except the one whose unique id is `but`) in lanes: see
    vehicles_on_lanes."""
    if len(table) == 0:
        return LaneOccupants.empty()
    projection = lane_map.project_many(table.positions[:, :2], table.headings)
    return vehicles_on_lanes(table, projection, but)


def vehicles_on_lanes(
    table: ObjectTable, placed: LaneProjections, but: int | None = None
) -> LaneOccupants:
    """The objects of `table` (placed: their footprint centres projected with their
    headings as hints) that stand on a lane, within half their width of its edge, with
    their speed along that lane; the one whose unique id is `but` left out."""
    if len(table) == 0:
        return LaneOccupants.empty()
    on_lane = np.abs(placed.lateral) <= (placed.width + table.sizes[:, 1]) / 2.0
    on_lane &= table.unique_ids != but
    direction = np.column_stack((np.cos(placed.heading), np.sin(placed.heading)))
    along = np.einsum("ij,ij->i", table.velocities[:, :2], direction)
    return LaneOccupants(
        placed.lane_index[on_lane],
        placed.s[on_lane],
        table.sizes[on_lane, 0] / 2.0,
        along[on_lane],
    )


def pedestrians_on_lanes(placed: LaneProjections) -> LaneOccupants:
    """The pedestrians (placed: their positions projected without a hint) within
    PEDESTRIAN_LANE_MARGIN_M of a lane's edge, as standing road users."""
    near = np.abs(placed.lateral) <= placed.width / 2.0 + PEDESTRIAN_LANE_MARGIN_M
    count = int(np.count_nonzero(near))
    return LaneOccupants(
        placed.lane_index[near],
        placed.s[near],
        np.full(count, PEDESTRIAN_HALF_DEPTH_M),
        np.zeros(count),
    )


def obstacles_on_lanes(table: ObjectTable, placed: LaneProjections) -> LaneOccupants:
    """The boxes of `table` (placed: their centres projected without a hint) that reach
    into a lane with the half diagonal of their footprint, as standing road users."""
    reach = np.hypot(table.sizes[:, 0], table.sizes[:, 1]) / 2.0
    on_lane = np.abs(placed.lateral) <= placed.width / 2.0 + reach
    return LaneOccupants(
        placed.lane_index[on_lane],
        placed.s[on_lane],
        reach[on_lane],
        np.zeros(int(np.count_nonzero(on_lane))),
    )
