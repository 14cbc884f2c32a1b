"""The `loop` map: a ~400 m oval, two lanes driven counter-clockwise, no lights."""

import math

import numpy as np

from egosim.world.map.builtin_origin import BUILTIN_GEOREF
from egosim.world.map.lanes import LaneMap
from egosim.world.map.polyline import arc
from egosim.world.map.road_network import RoadNetworkBuilder, RoadSpec

STRAIGHT_M = 75.0
RADIUS_M = 40.0
LANE_WIDTH_M = 3.5
SPEED_LIMIT_MPS = 50.0 / 3.6


def build_loop() -> LaneMap:
    """Two roads joined end to start into an oval around the origin: R1 is the east half
    (north-bound: half of the south straight, the east bend, half of the north straight),
    R2 the west half (south-bound). The reference line is the inner kerb, so lane 1 is the
    inner lane. Roads meet mid-straight, where their lane ends join exactly."""
    half = STRAIGHT_M / 2
    east = np.vstack(([[0.0, -RADIUS_M]], arc((half, 0.0), RADIUS_M, -math.pi / 2, math.pi)))
    east = np.vstack((east, [[0.0, RADIUS_M]]))
    west = -east
    builder = RoadNetworkBuilder(LANE_WIDTH_M)
    for road_id, reference in enumerate((east, west), start=1):
        builder.add_road(RoadSpec(road_id, reference, 2, 0, SPEED_LIMIT_MPS))
    builder.link(1, 2)
    builder.link(2, 1)
    return builder.build("loop", BUILTIN_GEOREF)
