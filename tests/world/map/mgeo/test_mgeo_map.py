import copy
import math

import numpy as np
import pytest
from tests.world.map.mgeo.sample_mgeo import (
    ARM_M,
    BOX_M,
    CURVE_CENTER,
    CURVE_RADIUS_M,
    LANE_M,
    mgeo_files,
)

from egosim.world.map import LaneMap, MapRecordError
from egosim.world.map.markings import (
    LineStyle,
    MarkingColor,
    MarkingKind,
    map_markings,
)
from egosim.world.map.mgeo import build_mgeo_map


def build(files: dict[str, object]) -> tuple[LaneMap, list[str]]:
    notes: list[str] = []
    return build_mgeo_map("sample", files, notes), notes


@pytest.fixture(scope="module")
def sample() -> tuple[LaneMap, list[str]]:
    return build(mgeo_files())


def test_links_become_lanes_and_lane_change_links_do_not(sample):
    lane_map, notes = sample
    # 5 incoming, 4 outgoing, 1 curve, 12 + 1 connectors; LC_W_2_1 is a manoeuvre.
    assert len(lane_map.lanes) == 23
    assert "LC_W_2_1" not in lane_map.lanes
    assert any("1 lane-change links" in note for note in notes)
    assert any("PL_S: pedestrian light ignored" in note for note in notes)


def test_successors_follow_nodes(sample):
    lane_map, _ = sample
    assert set(lane_map.lane("L_S_in").successors) == {"C_SN", "C_SE", "C_SW"}
    assert lane_map.lane("C_SN").successors == ("L_N_out",)
    assert lane_map.lane("L_N_out").successors == ("L_N_curve",)
    assert set(lane_map.lane("L_E_out").predecessors) == {"C_NE", "C_SE", "C_WE", "C_WE2"}


def test_connectors_are_junction_lanes(sample):
    lane_map, _ = sample
    assert lane_map.lane("C_SN").is_junction
    assert not lane_map.lane("L_S_in").is_junction
    assert not lane_map.lane("L_N_out").is_junction


def test_lane_change_neighbours(sample):
    lane_map, _ = sample
    assert lane_map.lane("L_W_in").right_neighbor == "L_W_in2"
    assert lane_map.lane("L_W_in2").left_neighbor == "L_W_in"
    assert lane_map.lane("L_W_in").left_neighbor is None


def test_speed_limits_are_metres_per_second(sample):
    lane_map, _ = sample
    assert lane_map.lane("L_S_in").speed_limit == pytest.approx(50 / 3.6)
    assert lane_map.lane("L_N_curve").speed_limit == pytest.approx(30 / 3.6)


def test_stop_lines_and_governing_lights(sample):
    lane_map, _ = sample
    for arm in "ENWS":
        lane = lane_map.lane(f"L_{arm}_in")
        assert lane.stop_line_s == pytest.approx(ARM_M)
        assert lane.traffic_light_ids == (f"TL_{arm}",)
    assert lane_map.lane("L_W_in2").traffic_light_ids == ("TL_W",)
    # TL_E lists the connectors past the line: it governs the lane arriving at the line.
    assert lane_map.traffic_lights["TL_E"].lane_ids == ("L_E_in",)
    assert lane_map.lane("C_EW").traffic_light_ids == ()


def test_light_types_and_facing(sample):
    lane_map, _ = sample
    lights = lane_map.traffic_lights
    assert lights["TL_N"].light_type == 2
    assert lights["TL_E"].light_type == 0
    # South arm traffic drives north, so its head faces south.
    assert lights["TL_S"].heading == pytest.approx(-math.pi / 2)
    assert lights["TL_E"].heading == pytest.approx(0.0)
    assert lights["TL_N"].position == pytest.approx((-2.5 * LANE_M, BOX_M, 5.0))


def test_synced_sets_are_approach_groups(sample):
    lane_map, _ = sample
    (site,) = lane_map.intersections.values()
    assert site.id == 1
    assert site.center == (0.0, 0.0)
    assert site.approach_groups == (("TL_N", "TL_S"), ("TL_E", "TL_W"))
    assert {lane_map.traffic_lights[i].intersection_id for i in site.light_ids} == {1}


def test_point_on_straight_lane_projects_to_lane_and_station(sample):
    lane_map, _ = sample
    # L_S_in runs north along x = LANE/2 from y = -(BOX + ARM).
    p = lane_map.project(LANE_M / 2 + 0.5, -60.0, heading=math.pi / 2)
    assert p.lane_id == "L_S_in"
    assert p.s == pytest.approx(BOX_M + ARM_M - 60.0)
    assert p.lateral == pytest.approx(-0.5)


@pytest.mark.parametrize("angle", [0.9 * math.pi, 0.75 * math.pi, 0.6 * math.pi])
def test_point_on_curve_projects_to_arc_length(sample, angle):
    lane_map, _ = sample
    radius = CURVE_RADIUS_M - 1.0
    x = CURVE_CENTER[0] + radius * math.cos(angle)
    y = CURVE_CENTER[1] + radius * math.sin(angle)
    p = lane_map.project(x, y, heading=angle - math.pi / 2)
    assert p.lane_id == "L_N_curve"
    # The arc is drawn with vertices 0.5 m apart (dθ = 0.01 rad); 1 m inside a vertex the
    # foot on either chord falls (R - r)·sin(dθ/2) = 5 mm short of the arc's station.
    assert p.s == pytest.approx(CURVE_RADIUS_M * (math.pi - angle), abs=6e-3)
    # Turning right, the centre of the curve lies to the right: inside is negative.
    assert p.lateral == pytest.approx(-1.0, abs=5e-3)


def test_widths_run_from_width_start_to_width_end():
    files = mgeo_files()
    link = next(r for r in files["link_set.json"] if r["idx"] == "L_S_in")
    link.update(
        width_start=3.0,
        width_end=4.0,
        points=[[1.75, -110.0, 0], [1.75, -60, 0], [1.75, -10, 0]],
    )
    lane_map, _ = build(files)
    assert lane_map.lane("L_S_in").widths == pytest.approx([3.0, 3.5, 4.0])


def test_widths_come_from_lane_boundaries_when_present():
    files = mgeo_files()
    files["lane_boundary_set.json"] = [
        {
            "idx": "B_left",
            "points": [[0.0, -120, 0], [0.0, 0, 0]],
            "lane_type": 501,
            "lane_color": "yellow",
            "lane_shape": ["Solid"],
            "lane_width": 0.15,
        },
        {
            "idx": "B_right",
            "points": [[3.8, -120, 0], [3.8, 0, 0]],
            "lane_type": 501,
            "lane_color": "white",
            "lane_shape": ["Broken"],
            "lane_width": 0.15,
        },
    ]
    link = next(r for r in files["link_set.json"] if r["idx"] == "L_S_in")
    link.update(lane_mark_left=["B_left"], lane_mark_right=["B_right"])
    lane_map, _ = build(files)
    assert lane_map.lane("L_S_in").widths == pytest.approx([3.8, 3.8])
    assert lane_map.lane("L_N_in").widths == pytest.approx([LANE_M, LANE_M])


def test_repeated_points_are_merged():
    files = mgeo_files()
    link = next(r for r in files["link_set.json"] if r["idx"] == "L_S_in")
    link["points"] = [[1.75, -110.0, 0], [1.75, -110.0, 0], [1.75, -10, 0]]
    lane_map, _ = build(files)
    assert len(lane_map.lane("L_S_in").centerline) == 2


def test_optional_files_may_be_absent():
    files = mgeo_files()
    for name in (
        "node_set.json",
        "traffic_light_set.json",
        "synced_traffic_light_set.json",
        "intersection_controller_set.json",
    ):
        del files[name]
    lane_map, _ = build(files)
    assert len(lane_map.lanes) == 23
    assert not lane_map.traffic_lights
    assert lane_map.lane("L_N_out").successors == ("L_N_curve",)


def test_light_without_synced_set_runs_alone():
    files = mgeo_files()
    files["synced_traffic_light_set.json"] = files["synced_traffic_light_set.json"][:1]
    files["intersection_controller_set.json"][0]["synced_signal_id_list"] = ["SL_NS"]
    lane_map, notes = build(files)
    assert lane_map.intersections[1].approach_groups == (("TL_N", "TL_S"),)
    alone = {i for i in lane_map.intersections if i != 1}
    assert {lane_map.intersections[i].light_ids for i in alone} == {("TL_E",), ("TL_W",)}
    assert any("TL_E: in no synced set" in note for note in notes)


def _broken(file: str, record: str | None, **fields: object) -> dict[str, object]:
    """The sample with fields of one record of `file` replaced (record None: the whole file)."""
    files = copy.deepcopy(mgeo_files())
    if record is None:
        files[file] = fields["whole"]
    else:
        next(r for r in files[file] if r["idx"] == record).update(fields)
    return files


@pytest.mark.parametrize(
    ("files", "source", "record", "reason"),
    [
        (_broken("link_set.json", "L_S_in", points="abc"), "link_set.json", "'L_S_in'", "points"),
        (
            _broken("link_set.json", "L_S_in", points=[[0, 0, 0]]),
            "link_set.json",
            "'L_S_in'",
            "two distinct points",
        ),
        (
            _broken("link_set.json", "L_S_in", max_speed="fast"),
            "link_set.json",
            "'L_S_in'",
            "max_speed",
        ),
        (
            _broken("link_set.json", "L_S_in", to_node_idx="nowhere"),
            "link_set.json",
            "'L_S_in'",
            "nowhere",
        ),
        (_broken("link_set.json", "C_SN", idx="L_S_in"), "link_set.json", "'L_S_in'", "repeats"),
        (_broken("link_set.json", None, whole={"idx": 1}), "link_set.json", "file", "list"),
        (
            _broken("traffic_light_set.json", "TL_N", point=None),
            "traffic_light_set.json",
            "'TL_N'",
            "point",
        ),
        (
            _broken(
                "global_info.json",
                None,
                whole={"global_coordinate_system": "Mars", "local_origin_in_global": [0, 0, 0]},
            ),
            "global_info.json",
            "global info",
            "Mars",
        ),
        (
            _broken("node_set.json", "N_S_in_end", on_stop_line="yes"),
            "node_set.json",
            "'N_S_in_end'",
            "on_stop_line",
        ),
    ],
)
def test_malformed_records_are_named(files, source, record, reason):
    with pytest.raises(MapRecordError) as caught:
        build(files)
    assert caught.value.source == source
    assert record in caught.value.record
    assert reason in caught.value.reason


def test_a_light_in_two_synced_sets_is_refused():
    files = mgeo_files()
    files["synced_traffic_light_set.json"][1]["signal_id_list"].append("TL_N")
    with pytest.raises(MapRecordError, match="TL_N is already in synced set SL_NS"):
        build(files)


def test_missing_link_set_is_named():
    files = mgeo_files()
    del files["link_set.json"]
    with pytest.raises(MapRecordError, match=r"link_set\.json: file: is missing"):
        build(files)


def test_lanes_end_on_their_nodes(sample):
    lane_map, _ = sample
    nodes = {n["idx"]: np.array(n["point"]) for n in mgeo_files()["node_set.json"]}
    for link in mgeo_files()["link_set.json"]:
        if link["idx"] in lane_map.lanes:
            line = lane_map.lane(link["idx"]).centerline
            assert line[0] == pytest.approx(nodes[link["from_node_idx"]], abs=1e-9)
            assert line[-1] == pytest.approx(nodes[link["to_node_idx"]], abs=1e-9)


def test_lane_boundaries_become_the_markings_they_describe():
    files = mgeo_files()
    files["lane_boundary_set.json"] = [
        {
            "idx": "centre",
            "points": [[0.0, -120, 0], [0.0, 0, 0]],
            "lane_type": 501,
            "lane_color": "yellow",
            "lane_shape": ["Solid", "Solid"],
            "lane_width": 0.15,
            "double_line_interval": 0.2,
        },
        {
            "idx": "lanes",
            "points": [[3.5, -120, 0], [3.5, 0, 0]],
            "lane_type": 503,
            "lane_color": "white",
            "lane_shape": ["Broken"],
            "lane_width": 0.12,
            "dash_interval_L1": 5.0,
            "dash_interval_L2": 8.0,
        },
        {
            "idx": "stop",
            "points": [[0.0, -10, 0], [3.5, -10, 0]],
            "lane_type": 530,
            "lane_color": "white",
            "lane_shape": "Solid",
            "lane_width": 0.45,
        },
        {"idx": "virtual", "points": [[7.0, -120, 0], [7.0, 0, 0]], "lane_shape": ["Solid"]},
    ]
    lane_map, notes = build(files)
    markings = {m.id: m for m in lane_map.markings}
    assert set(markings) == {"centre", "lanes", "stop"}
    centre, lanes, stop = markings["centre"], markings["lanes"], markings["stop"]
    assert (centre.color, centre.lines, centre.double_gap_m) == (
        MarkingColor.YELLOW,
        (LineStyle.SOLID, LineStyle.SOLID),
        0.2,
    )
    assert (lanes.color, lanes.lines, lanes.width_m) == (
        MarkingColor.WHITE,
        (LineStyle.DASHED,),
        0.12,
    )
    assert (lanes.dash_length_m, lanes.dash_gap_m) == (5.0, 8.0)
    assert (stop.kind, stop.width_m) == (MarkingKind.STOP_LINE, 0.45)
    assert any("virtual" in note and "no painted line" in note for note in notes)
    # A map that lists its paint is painted with it, not from its lane graph.
    assert map_markings(lane_map) == lane_map.markings
