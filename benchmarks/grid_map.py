"""A synthetic map for benchmarks: an n x n grid of signalised four-way junctions."""

from __future__ import annotations

import numpy as np

from egosim.world.map import LaneMap
from egosim.world.map.builtin_origin import BUILTIN_GEOREF
from egosim.world.map.road_network import JunctionSpec, RoadNetworkBuilder, RoadSpec

LANE_WIDTH_M = 3.5
JUNCTION_RADIUS_M = 14.0
SPEED_LIMIT_MPS = 50 / 3.6


def grid_map(n: int, spacing: float, name: str = "grid") -> LaneMap:
    """Junctions `spacing` metres apart, two lanes each way on every road between them."""
    builder = RoadNetworkBuilder(LANE_WIDTH_M)
    for row in range(n):
        for column in range(n):
            centre = (column * spacing, row * spacing)
            builder.add_junction(JunctionSpec(1 + row * n + column, centre, JUNCTION_RADIUS_M))
    road_id = 0
    for row in range(n):
        for column in range(n - 1):
            for a, b in (((column, row), (column + 1, row)), ((row, column), (row, column + 1))):
                road_id += 1
                reference = np.array([a, b], dtype=float) * spacing
                ja, jb = (1 + p[1] * n + p[0] for p in (a, b))
                builder.add_road(RoadSpec(road_id, reference, 2, 2, SPEED_LIMIT_MPS, ja, jb))
    return builder.build(name, BUILTIN_GEOREF)
