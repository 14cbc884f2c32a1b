"""The `straight` map: 1 km of two-way road, two lanes each way, 100 km/h, no junctions."""

import numpy as np

from egosim.world.map.builtin_origin import BUILTIN_GEOREF
from egosim.world.map.lanes import LaneMap
from egosim.world.map.road_network import RoadNetworkBuilder, RoadSpec

LENGTH_M = 1000.0
LANE_WIDTH_M = 3.5
SPEED_LIMIT_MPS = 100.0 / 3.6


def build_straight() -> LaneMap:
    """Reference line along +x from (0, 0): R1_E_1/R1_E_2 south of it, R1_W_1/R1_W_2 north."""
    builder = RoadNetworkBuilder(LANE_WIDTH_M)
    reference = np.array([[0.0, 0.0], [LENGTH_M, 0.0]])
    builder.add_road(RoadSpec(1, reference, 2, 2, SPEED_LIMIT_MPS))
    return builder.build("straight", BUILTIN_GEOREF)
