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
    """Four roads around the origin, joined end to start: R1 south straight (east-bound),
    R2 east half circle (north-bound), R3 north straight (west-bound), R4 west half circle
    (south-bound). The reference line is the inner kerb; lane 1 is the inner lane."""
    half = STRAIGHT_M / 2
    references = (
        np.array([[-half, -RADIUS_M], [half, -RADIUS_M]]),
        arc((half, 0.0), RADIUS_M, -math.pi / 2, math.pi),
        np.array([[half, RADIUS_M], [-half, RADIUS_M]]),
        arc((-half, 0.0), RADIUS_M, math.pi / 2, math.pi),
    )
    builder = RoadNetworkBuilder(LANE_WIDTH_M)
    for road_id, reference in enumerate(references, start=1):
        builder.add_road(RoadSpec(road_id, reference, 2, 0, SPEED_LIMIT_MPS))
    for road_id in range(1, 5):
        builder.link(road_id, road_id % 4 + 1)
    return builder.build("loop", BUILTIN_GEOREF)
