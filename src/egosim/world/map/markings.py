"""Paint on the road: lane lines and stop lines, from a map's own data or its lane graph.

A map file that describes its paint (MGeo's lane_boundary_set.json) gives the markings
it lists. A map without such data (the built-in maps, a file that lists none) is painted
from its lane graph by the conventions of Korean roads, which MORAI's maps follow:

- between two lanes of the same direction: a white dashed line (3 m paint, 5 m gap);
- between the two directions of a road: a yellow double solid centre line;
- the outer edge of a carriageway: a white solid line;
- a stop line (0.45 m, white) across every lane that ends at one;
- nothing inside junctions.

Widths are the painted width of one line (0.15 m for lane lines); a double line is two
lines `double_gap_m` apart between their inner edges, centred on the boundary.
"""

from __future__ import annotations

import numpy as np

from egosim.world.arrays import FloatArray
from egosim.world.map.lanes import Lane, LaneMap
from egosim.world.map.polyline import offset_left
from egosim.world.map.road_marking import (
    DASH_GAP_M,
    DASH_LENGTH_M,
    DOUBLE_GAP_M,
    LANE_LINE_WIDTH_M,
    STOP_LINE_WIDTH_M,
    LineStyle,
    MarkingColor,
    MarkingKind,
    RoadMarking,
)

__all__ = [
    "DASH_GAP_M",
    "DASH_LENGTH_M",
    "DOUBLE_GAP_M",
    "LANE_LINE_WIDTH_M",
    "STOP_LINE_WIDTH_M",
    "LineStyle",
    "MarkingColor",
    "MarkingKind",
    "RoadMarking",
    "lane_edges",
    "lane_graph_markings",
    "map_markings",
]

# A lane whose left edge is within this of an opposite lane's edge shares a centre line.
_SHARED_EDGE_TOLERANCE_M = 0.5


def map_markings(lane_map: LaneMap) -> tuple[RoadMarking, ...]:
    """The markings a map's data lists, else the ones its lane graph implies."""
    return lane_map.markings or lane_graph_markings(lane_map)


def lane_graph_markings(lane_map: LaneMap) -> tuple[RoadMarking, ...]:
    """Lane lines and stop lines painted by the conventions in the module docstring."""
    markings: list[RoadMarking] = []
    for lane in lane_map.lanes.values():
        if lane.is_junction:
            continue
        left, right = lane_edges(lane)
        if lane.right_neighbor is not None:
            markings.append(_line(f"{lane.id}/right", right, MarkingColor.WHITE, LineStyle.DASHED))
        else:
            markings.append(_line(f"{lane.id}/right", right, MarkingColor.WHITE, LineStyle.SOLID))
        if lane.left_neighbor is None:
            opposite = _opposite_lane(lane_map, lane, left)
            if opposite is None:
                markings.append(_line(f"{lane.id}/left", left, MarkingColor.WHITE, LineStyle.SOLID))
            elif lane.id < opposite:
                markings.append(
                    RoadMarking(
                        f"{lane.id}/centre",
                        left,
                        MarkingColor.YELLOW,
                        (LineStyle.SOLID, LineStyle.SOLID),
                    )
                )
        if lane.stop_line_s is not None:
            markings.append(_stop_line(lane_map, lane))
    return tuple(markings)


def lane_edges(lane: Lane, margin_m: float = 0.0) -> tuple[FloatArray, FloatArray]:
    """The left and right edges of a lane (N, 3), `margin_m` beyond its width, following
    its centreline's z."""
    centre = lane.centerline
    normals = offset_left(centre[:, :2], 1.0) - centre[:, :2]
    half = (lane.widths / 2.0 + margin_m)[:, None]
    left = np.column_stack((centre[:, :2] + half * normals, centre[:, 2]))
    right = np.column_stack((centre[:, :2] - half * normals, centre[:, 2]))
    return left, right


def _line(
    marking_id: str, points: FloatArray, color: MarkingColor, style: LineStyle
) -> RoadMarking:
    return RoadMarking(marking_id, points, color, (style,))


def _opposite_lane(lane_map: LaneMap, lane: Lane, left: FloatArray) -> str | None:
    """The lane of the other direction whose left edge is this lane's left edge, if any.

    Looks half a metre past the middle of this lane's left edge: that point lies inside
    such a lane, left of its centreline.
    """
    middle = len(left) // 2
    a, b = left[max(middle - 1, 0), :2], left[min(middle + 1, len(left) - 1), :2]
    along = (b - a) / max(float(np.hypot(*(b - a))), 1e-9)
    beyond = left[middle, :2] + np.array([-along[1], along[0]]) * _SHARED_EDGE_TOLERANCE_M
    reverse = float(np.arctan2(-along[1], -along[0]))
    found = lane_map.project(float(beyond[0]), float(beyond[1]), reverse)
    if found.lane_id == lane.id or lane_map.lane(found.lane_id).is_junction:
        return None
    turn = abs(np.remainder(found.heading - reverse + np.pi, 2 * np.pi) - np.pi)
    inside_left_half = 0.0 <= found.lateral <= found.width / 2.0
    return found.lane_id if turn < np.pi / 2 and inside_left_half else None


def _stop_line(lane_map: LaneMap, lane: Lane) -> RoadMarking:
    assert lane.stop_line_s is not None
    # The line's far edge on the stop station, so a car stopping there stands behind it.
    s = max(lane.stop_line_s - STOP_LINE_WIDTH_M / 2.0, 0.0)
    x, y, z, heading = lane_map.pose_at(lane.id, s)
    width = float(np.interp(s, lane.stations, lane.widths))
    across = np.array([-np.sin(heading), np.cos(heading)]) * width / 2.0
    points = np.array([[x + across[0], y + across[1], z], [x - across[0], y - across[1], z]])
    return RoadMarking(
        f"{lane.id}/stop",
        points,
        MarkingColor.WHITE,
        (LineStyle.SOLID,),
        kind=MarkingKind.STOP_LINE,
        width_m=STOP_LINE_WIDTH_M,
    )
