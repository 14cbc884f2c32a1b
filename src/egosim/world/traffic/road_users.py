"""Placing arbitrary objects on lanes, for agents that react to whoever stands there."""

from __future__ import annotations

import numpy as np

from egosim.world.map import LaneMap
from egosim.world.traffic.leaders import LaneOccupants
from egosim.world.traffic.objects import ObjectTable


def lane_occupants_of(
    table: ObjectTable, lane_map: LaneMap, but: int | None = None
) -> LaneOccupants:
    """The objects of `table` (except the one whose unique id is `but`) that stand on a
    lane (within half their width of its edge), with their speed along that lane."""
    if len(table) == 0:
        return LaneOccupants.empty()
    projection = lane_map.project_many(table.positions[:, :2], table.headings)
    on_lane = np.abs(projection.lateral) <= (projection.width + table.sizes[:, 1]) / 2.0
    on_lane &= table.unique_ids != but
    direction = np.column_stack((np.cos(projection.heading), np.sin(projection.heading)))
    along = np.einsum("ij,ij->i", table.velocities[:, :2], direction)
    return LaneOccupants(
        projection.lane_index[on_lane],
        projection.s[on_lane],
        table.sizes[on_lane, 0] / 2.0,
        along[on_lane],
    )
