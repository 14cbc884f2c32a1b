"""The `town` map: a signalised 3 x 3-block grid inside a two-way ring road.

Grid lines run at x, y in {-270, -90, 90, 270} m (180 m blocks). Grid junction ids are
1..16, row by row from the south-west (id = 1 + 4 row + column). Each grid line runs on
past the outer junctions to a T-junction on the ring, a rounded square of half-size 400 m
(corner radius 60 m); those junctions are 17..32, counter-clockwise from the south-west.
Grid roads are 50 km/h, the ring 60 km/h, every road two lanes each way, 3.5 m wide.
"""

from __future__ import annotations

import math

import numpy as np

from egosim.world.map.builtin_origin import BUILTIN_GEOREF
from egosim.world.map.lanes import LaneMap, Sidewalk
from egosim.world.map.light_type import LightType
from egosim.world.map.polyline import arc, between, stations
from egosim.world.map.road_network import (
    JunctionSpec,
    RoadNetworkBuilder,
    RoadSpec,
    standard_light_type,
)

GRID_LINES_M = (-270.0, -90.0, 90.0, 270.0)
RING_HALF_SIZE_M = 400.0
RING_CORNER_RADIUS_M = 60.0
LANE_WIDTH_M = 3.5
LANES_PER_DIRECTION = 2
GRID_SPEED_MPS = 50.0 / 3.6
RING_SPEED_MPS = 60.0 / 3.6
# Big enough that the four carriageways (7 m half-width) meet without overlapping.
JUNCTION_RADIUS_M = 14.0
# Sidewalks run this far from the grid line: 7 m of carriageway plus a 3 m verge.
SIDEWALK_INSET_M = 10.0
# Downtown junctions give left turns a phase of their own; one ring junction flashes.
CENTRAL_JUNCTIONS = frozenset({6, 7, 10, 11})
FLASHING_JUNCTION = 17
# The stem of this ring T-junction (arriving from the north) has a left-only inner lane
# and a right-only outer lane, and is served alone: it carries a red / yellow /
# left-arrow head (type 1), so the town shows every head type of the protocol.
LEFT_ARROW_ONLY_APPROACH = (18, "N")


def grid_junction_id(row: int, column: int) -> int:
    return 1 + 4 * row + column


def build_town() -> LaneMap:
    builder = RoadNetworkBuilder(LANE_WIDTH_M)
    lines = GRID_LINES_M
    for row, y in enumerate(lines):
        for column, x in enumerate(lines):
            number = grid_junction_id(row, column)
            builder.add_junction(
                JunctionSpec(
                    number,
                    (x, y),
                    JUNCTION_RADIUS_M,
                    protected_lefts=number in CENTRAL_JUNCTIONS,
                )
            )
    ring_centres = _ring_junction_centres()
    for k, centre in enumerate(ring_centres):
        builder.add_junction(JunctionSpec(17 + k, centre, JUNCTION_RADIUS_M))

    road_ids = iter(range(1, 1000))

    def grid_road(a: tuple[float, float], b: tuple[float, float], ja: int, jb: int) -> None:
        reference = np.array([a, b])
        spec = RoadSpec(
            next(road_ids),
            reference,
            LANES_PER_DIRECTION,
            LANES_PER_DIRECTION,
            GRID_SPEED_MPS,
            ja,
            jb,
        )
        builder.add_road(spec)

    for row, y in enumerate(lines):
        for column in range(3):
            a, b = (lines[column], y), (lines[column + 1], y)
            grid_road(a, b, grid_junction_id(row, column), grid_junction_id(row, column + 1))
    for column, x in enumerate(lines):
        for row in range(3):
            a, b = (x, lines[row]), (x, lines[row + 1])
            grid_road(a, b, grid_junction_id(row, column), grid_junction_id(row + 1, column))

    half = RING_HALF_SIZE_M
    for k, coordinate in enumerate(lines):
        # Ring junctions: south side 17..20 (west to east), east 21..24 (south to north),
        # north 25..28 (east to west), west 29..32 (north to south).
        grid_road((coordinate, -half), (coordinate, lines[0]), 17 + k, grid_junction_id(0, k))
        grid_road((half, coordinate), (lines[3], coordinate), 21 + k, grid_junction_id(k, 3))
        grid_road((coordinate, half), (coordinate, lines[3]), 28 - k, grid_junction_id(3, k))
        grid_road((-half, coordinate), (lines[0], coordinate), 32 - k, grid_junction_id(k, 0))

    ring = _ring_centreline()
    ring_length = float(stations(ring)[-1])
    doubled = np.vstack((ring, ring[1:]))
    ring_stations = [_ring_station(c) for c in ring_centres]
    for k, start in enumerate(ring_stations):
        end = ring_stations[(k + 1) % len(ring_stations)]
        if end <= start:
            end += ring_length
        reference = between(doubled, start, end)
        spec = RoadSpec(
            next(road_ids),
            reference,
            LANES_PER_DIRECTION,
            LANES_PER_DIRECTION,
            RING_SPEED_MPS,
            17 + k,
            17 + (k + 1) % 16,
        )
        builder.add_road(spec)

    return builder.build("town", BUILTIN_GEOREF, _light_type, _block_sidewalks())


def _light_type(junction_id: int, arm: str, can_turn_left: bool) -> LightType:
    if junction_id == FLASHING_JUNCTION:
        return LightType.FLASHING_YELLOW
    if (junction_id, arm) == LEFT_ARROW_ONLY_APPROACH:
        return LightType.RYG_LEFT
    return standard_light_type(junction_id, arm, can_turn_left)


def _ring_junction_centres() -> list[tuple[float, float]]:
    half, lines = RING_HALF_SIZE_M, GRID_LINES_M
    return [
        *((x, -half) for x in lines),
        *((half, y) for y in lines),
        *((x, half) for x in reversed(lines)),
        *((-half, y) for y in reversed(lines)),
    ]


def _ring_centreline() -> np.ndarray:
    """Closed counter-clockwise rounded square, starting where the south side's straight begins."""
    h, r = RING_HALF_SIZE_M, RING_CORNER_RADIUS_M
    c = h - r
    quarter = math.pi / 2
    pieces = [
        arc((c, -c), r, -quarter, quarter),
        arc((c, c), r, 0.0, quarter),
        arc((-c, c), r, quarter, quarter),
        arc((-c, -c), r, 2 * quarter, quarter),
    ]
    start = np.array([[-c, -h]])
    return np.vstack((start, *pieces))


def _ring_station(point: tuple[float, float]) -> float:
    """Station on `_ring_centreline` of a point on one of its straight sides."""
    h, r = RING_HALF_SIZE_M, RING_CORNER_RADIUS_M
    side = 2 * (h - r)
    corner = math.pi / 2 * r
    x, y = point
    if math.isclose(y, -h):
        return x + (h - r)
    if math.isclose(x, h):
        return side + corner + y + (h - r)
    if math.isclose(y, h):
        return 2 * (side + corner) + (h - r) - x
    return 3 * (side + corner) + (h - r) - y


def _block_sidewalks() -> list[Sidewalk]:
    """A closed walk around each of the nine grid blocks, counter-clockwise."""
    lines, inset = GRID_LINES_M, SIDEWALK_INSET_M
    walks = []
    for row in range(3):
        for column in range(3):
            x0, x1 = lines[column] + inset, lines[column + 1] - inset
            y0, y1 = lines[row] + inset, lines[row + 1] - inset
            points = np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1], [x0, y0]])
            walks.append(Sidewalk(f"SW{1 + 3 * row + column}", points))
    return walks
