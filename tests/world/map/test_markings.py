"""Road markings painted from the lane graph, by the built-in maps' conventions."""

from __future__ import annotations

import numpy as np

from egosim.world.map import build_builtin_map
from egosim.world.map.markings import (
    LineStyle,
    MarkingColor,
    MarkingKind,
    lane_graph_markings,
    map_markings,
)


def _lateral_lines(map_name: str) -> dict[float, tuple[MarkingColor, tuple[LineStyle, ...]]]:
    """Each lane line of a map by its (constant) y, for maps whose roads run along x."""
    lines = {}
    for marking in lane_graph_markings(build_builtin_map(map_name)):
        if marking.kind is MarkingKind.LANE_LINE:
            y = np.unique(np.round(marking.points[:, 1], 6))
            assert len(y) == 1
            lines[float(y[0])] = (marking.color, marking.lines)
    return lines


def test_the_straight_road_has_a_yellow_double_centre_line_dashed_lanes_and_solid_edges() -> None:
    solid, dashed = (LineStyle.SOLID,), (LineStyle.DASHED,)
    assert _lateral_lines("straight") == {
        -7.0: (MarkingColor.WHITE, solid),
        -3.5: (MarkingColor.WHITE, dashed),
        0.0: (MarkingColor.YELLOW, (LineStyle.SOLID, LineStyle.SOLID)),
        3.5: (MarkingColor.WHITE, dashed),
        7.0: (MarkingColor.WHITE, solid),
    }


def test_a_one_way_road_has_no_centre_line() -> None:
    markings = lane_graph_markings(build_builtin_map("loop"))
    assert markings
    assert all(m.color is MarkingColor.WHITE for m in markings)


def test_every_stop_line_of_the_town_is_painted_across_its_lane_and_junctions_are_bare() -> None:
    town = build_builtin_map("town")
    markings = map_markings(town)
    stops = [m for m in markings if m.kind is MarkingKind.STOP_LINE]
    stopping = [lane for lane in town.lanes.values() if lane.stop_line_s is not None]
    assert len(stops) == len(stopping) > 0
    for marking in stops:
        lane = town.lane(marking.id.removesuffix("/stop"))
        across = float(np.hypot(*(marking.points[1, :2] - marking.points[0, :2])))
        assert across == lane.widths[0]
    junction_ids = {lane.id for lane in town.lanes.values() if lane.is_junction}
    assert not any(m.id.split("/")[0] in junction_ids for m in markings)
