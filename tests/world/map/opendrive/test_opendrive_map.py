import math
from pathlib import Path

import pytest
from pyproj import CRS, Transformer
from tests.world.traffic.scenes import run, world_from

from egosim.sensors import GpsModel
from egosim.sensors.frames import Pose
from egosim.world.map import LaneMap, MapRecordError
from egosim.world.map.markings import LineStyle, MarkingColor
from egosim.world.map.opendrive import build_opendrive_map

JUNCTION_XODR = Path(__file__).parents[3] / "data" / "maps" / "junction.xodr"
TM_CENTRAL = "+proj=tmerc +lat_0=37.5 +lon_0=127 +k=1 +x_0=200000 +y_0=500000 +ellps=GRS80"
LANE_M = 3.5
# Road 5 starts at (0, 110) heading north on a right-hand quarter circle of radius 50.
CURVE_CENTER = (50.0, 110.0)
CURVE_RADIUS_M = 50.0


def build(text: str) -> tuple[LaneMap, list[str]]:
    notes: list[str] = []
    return build_opendrive_map("test", text, notes), notes


@pytest.fixture(scope="module")
def junction() -> tuple[LaneMap, list[str]]:
    return build(JUNCTION_XODR.read_text())


def single_road(
    lanes: str,
    lane_offset: str = '<laneOffset s="0" a="0" b="0" c="0" d="0"/>',
    road_attributes: str = "",
    extra: str = "",
) -> str:
    """A document with one 100 m road along +x from the origin."""
    return f"""<OpenDRIVE><header revMajor="1" revMinor="6"/>
      <road id="7" length="100" junction="-1" {road_attributes}>
        <planView><geometry s="0" x="0" y="0" hdg="0" length="100"><line/></geometry></planView>
        <elevationProfile><elevation s="0" a="2" b="0.01" c="0" d="0"/></elevationProfile>
        <lanes>{lane_offset}<laneSection s="0">{lanes}</laneSection></lanes>
      </road>{extra}</OpenDRIVE>"""


def lane(lane_id: int, width: str = 'a="3.5" b="0" c="0" d="0"', kind: str = "driving") -> str:
    return f'<lane id="{lane_id}" type="{kind}"><width sOffset="0" {width}/></lane>'


def test_driving_lanes_of_every_road_become_lanes(junction):
    lane_map, notes = junction
    # Four arms with a lane each way, road 5 with three lanes, six junction connectors.
    assert len(lane_map.lanes) == 4 * 2 + 3 + 6
    assert notes == ["road 4: signal PED4 (type 1000002) is not a vehicle light, ignored"]


def test_lanes_link_through_the_junction(junction):
    lane_map, _ = junction
    # South arm (road 4) lane 1 drives north into the junction: straight, left and right.
    assert set(lane_map.lane("4_0_1").successors) == {"10_0_-1", "14_0_-1", "15_0_-1"}
    assert lane_map.lane("10_0_-1").successors == ("2_0_-1",)
    assert lane_map.lane("14_0_-1").successors == ("3_0_-1",)
    assert lane_map.lane("15_0_-1").successors == ("1_0_-1",)
    assert lane_map.lane("2_0_-1").successors == ("5_0_-1",)
    assert lane_map.lane("5_0_1").successors == ("2_0_1",)
    assert lane_map.lane("10_0_-1").is_junction
    assert not lane_map.lane("4_0_1").is_junction


def test_lanes_join_end_to_start(junction):
    lane_map, _ = junction
    for lane in lane_map.lanes.values():
        for successor in lane.successors:
            start = lane_map.lane(successor).centerline[0]
            assert lane.centerline[-1] == pytest.approx(start, abs=1e-6)


def test_connector_turns_follow_their_arcs(junction):
    lane_map, _ = junction
    # Left turn: reference radius 10, lane -1 lies 1.75 m outside it.
    left = lane_map.lane("14_0_-1")
    assert left.length == pytest.approx((10 + LANE_M / 2) * math.pi / 2, rel=1e-4)
    right = lane_map.lane("15_0_-1")
    assert right.length == pytest.approx((10 - LANE_M / 2) * math.pi / 2, rel=1e-4)


def test_same_direction_lanes_are_lane_change_neighbours(junction):
    lane_map, _ = junction
    assert lane_map.lane("5_0_-1").right_neighbor == "5_0_-2"
    assert lane_map.lane("5_0_-2").left_neighbor == "5_0_-1"
    assert lane_map.lane("5_0_-1").left_neighbor is None  # lane 1 drives the other way


def test_lane_speed_overrides_road_type_speed(junction):
    lane_map, _ = junction
    assert lane_map.lane("5_0_-1").speed_limit == pytest.approx(40 / 3.6)
    assert lane_map.lane("5_0_1").speed_limit == pytest.approx(50 / 3.6)


def test_signals_govern_the_stop_lines_of_incoming_lanes(junction):
    lane_map, _ = junction
    for road in "1234":
        incoming = lane_map.lane(f"{road}_0_1")
        assert incoming.traffic_light_ids == (f"TL{road}",)
        assert incoming.stop_line_s == pytest.approx(incoming.length)
        assert lane_map.lane(f"{road}_0_-1").traffic_light_ids == ()


def test_signal_heads_stand_at_s_t_and_face_their_traffic(junction):
    lane_map, _ = junction
    south = lane_map.traffic_lights["TL4"]
    # Road 4 starts at (0, -10) heading south; t = 5 is on its left (east), zOffset 5.
    assert south.position == pytest.approx((5.0, -10.0, 5.0))
    # It governs northbound traffic, so it faces south.
    assert south.heading == pytest.approx(-math.pi / 2)
    assert lane_map.traffic_lights["TL3"].light_type == 1
    assert lane_map.traffic_lights["TL1"].light_type == 0


def test_junction_controllers_are_approach_groups(junction):
    lane_map, _ = junction
    (site,) = lane_map.intersections.values()
    assert site.id == 100
    assert site.approach_groups == (("TL2", "TL4"), ("TL1", "TL3"))
    assert {lane_map.traffic_lights[i].intersection_id for i in site.light_ids} == {100}


@pytest.mark.parametrize(("lane_id", "radius"), [("5_0_-1", 48.25), ("5_0_-2", 44.75)])
@pytest.mark.parametrize("angle", [0.8 * math.pi, 0.6 * math.pi])
def test_point_on_curved_lane_projects_to_lane_and_station(junction, lane_id, radius, angle):
    lane_map, _ = junction
    r = radius + 0.3
    x = CURVE_CENTER[0] + r * math.cos(angle)
    y = CURVE_CENTER[1] + r * math.sin(angle)
    p = lane_map.project(x, y, heading=angle - math.pi / 2)
    assert p.lane_id == lane_id
    # Vertices sit 0.02 rad apart on the arc: 0.3 m off it, the foot on a chord lies within
    # 0.3·sin(0.01) = 3 mm of the arc's station, and chords within 2.5 mm of the arc.
    assert p.s == pytest.approx(radius * (math.pi - angle), abs=4e-3)
    assert p.lateral == pytest.approx(0.3, abs=4e-3)


def test_gps_gives_the_projection_lat_lon_around_the_header_offset(junction):
    lane_map, _ = junction
    fix = GpsModel(lane_map.georef).measure(Pose(x=25.0, y=-40.0, z=1.0))
    crs = CRS.from_proj4(TM_CENTRAL)
    lon, lat = Transformer.from_crs(crs, crs.geodetic_crs, always_xy=True).transform(
        1000.0 + 25.0, 2000.0 - 40.0
    )
    assert (fix.latitude, fix.longitude) == pytest.approx((lat, lon), abs=1e-9)
    assert fix.altitude == pytest.approx(31.0)


def test_lane_offset_and_width_polynomials_place_the_lanes():
    # laneOffset 1 m; lane -1 widens from 3 m to 4 m; lane -2 stays 2 m outside it.
    text = single_road(
        "<right>"
        + lane(-1, 'a="3" b="0.01" c="0" d="0"')
        + lane(-2, 'a="2" b="0" c="0" d="0"')
        + "</right>",
        lane_offset='<laneOffset s="0" a="1" b="0" c="0" d="0"/>',
    )
    lane_map, _ = build(text)
    s = lane_map.lane("7_0_-1").centerline[:, 0]
    width = 3 + 0.01 * s
    assert lane_map.lane("7_0_-1").centerline[:, 1] == pytest.approx(1 - width / 2)
    assert lane_map.lane("7_0_-1").widths == pytest.approx(width)
    assert lane_map.lane("7_0_-2").centerline[:, 1] == pytest.approx(1 - width - 1)
    assert lane_map.lane("7_0_-1").centerline[:, 2] == pytest.approx(2 + 0.01 * s)


def test_left_lanes_drive_against_s_and_lht_swaps_them():
    both = f"<left>{lane(1)}</left><right>{lane(-1)}</right>"
    rht, _ = build(single_road(both))
    assert rht.lane("7_0_-1").centerline[0, 0] == 0.0
    assert rht.lane("7_0_1").centerline[0, 0] == 100.0
    lht, _ = build(single_road(both, road_attributes='rule="LHT"'))
    assert lht.lane("7_0_1").centerline[0, 0] == 0.0
    assert lht.lane("7_0_-1").centerline[0, 0] == 100.0


def test_non_driving_lanes_shift_but_do_not_become_lanes():
    text = single_road(f"<right>{lane(-1, kind='sidewalk')}{lane(-2)}</right>")
    lane_map, _ = build(text)
    assert set(lane_map.lanes) == {"7_0_-2"}
    assert lane_map.lane("7_0_-2").centerline[0, 1] == pytest.approx(-1.5 * LANE_M)


def test_sidewalk_lanes_become_walkways_along_their_centres():
    sidewalk_width = 'a="2.0" b="0" c="0" d="0"'
    text = single_road(f"<right>{lane(-1)}{lane(-2, sidewalk_width, 'sidewalk')}</right>")
    lane_map, _ = build(text)
    walkway = lane_map.sidewalks["7_0_-2"].points
    assert walkway[0, :2] == pytest.approx((0.0, -LANE_M - 1.0))
    assert walkway[-1, :2] == pytest.approx((100.0, -LANE_M - 1.0))
    # On the road's elevation profile (2 m at s = 0, rising 1 %).
    assert walkway[-1, 2] == pytest.approx(3.0)

    scenario = {
        "map": "test",
        "ego": {"start": {"lane": "7_0_-1", "s": 5.0}},
        "pedestrians": [{"sidewalk": "7_0_-2", "speed_mps": 1.0}],
    }
    world = world_from(scenario, lane_map)
    run(world, 10.0)
    assert world.pedestrians.position[0] == pytest.approx((10.0, -LANE_M - 1.0))


def two_way_road_with(objects: str) -> str:
    """single_road with a 3.5 m lane each way and `objects` on the road."""
    text = single_road(f"<left>{lane(1)}</left><right>{lane(-1)}</right>")
    return text.replace("</lanes>", f"</lanes><objects>{objects}</objects>")


@pytest.mark.parametrize(
    "crosswalk",
    [
        # A box: 4 m along the road (u, hdg 0), 12 m across it.
        '<object id="9" type="crosswalk" s="50" t="0" hdg="0" length="4" width="12"/>',
        # The same box as an outline of road corners.
        '<object id="9" type="crosswalk" s="50" t="0"><outline>'
        '<cornerRoad s="48" t="-6" dz="0" height="0"/><cornerRoad s="52" t="-6" dz="0" height="0"/>'
        '<cornerRoad s="52" t="6" dz="0" height="0"/><cornerRoad s="48" t="6" dz="0" height="0"/>'
        "</outline></object>",
        # And as local corners of an object turned a quarter turn.
        '<object id="9" type="crosswalk" s="50" t="0" hdg="1.5707963267948966"><outline>'
        '<cornerLocal u="-6" v="-2" z="0"/><cornerLocal u="6" v="-2" z="0"/>'
        '<cornerLocal u="6" v="2" z="0"/><cornerLocal u="-6" v="2" z="0"/>'
        "</outline></object>",
    ],
)
def test_crosswalk_objects_cross_the_road_square(crosswalk):
    lane_map, _ = build(two_way_road_with(crosswalk))
    walk = lane_map.crosswalks["7_9"]
    assert walk.start == pytest.approx((50.0, -6.0))
    assert walk.end == pytest.approx((50.0, 6.0))
    assert walk.width == pytest.approx(4.0)
    assert walk.intersection_id is None


def test_a_pedestrian_crosses_an_unsignalised_crosswalk_and_a_car_waits():
    text = two_way_road_with(
        '<object id="9" type="crosswalk" s="50" t="0" hdg="0" length="4" width="12"/>'
    )
    lane_map, _ = build(text)
    scenario = {
        "map": "test",
        "ego": {"start": {"lane": "7_0_1", "s": 5.0}},
        "npcs": [{"start": {"lane": "7_0_-1", "s": 20.0}, "speed_mps": 8.0}],
        "pedestrians": [{"crosswalk": "7_9", "speed_mps": 1.0}],
    }
    world = world_from(scenario, lane_map)
    run(world, 6.0)
    # Six seconds at 1 m/s from the far kerb: in the middle of the road.
    assert world.pedestrians.position[0] == pytest.approx((50.0, 0.0), abs=0.05)
    front = world.npcs.s[0] + world.npcs.dims[0, 0] / 2.0
    assert front < 48.0
    assert world.npcs.speed[0] < 0.5


def test_missing_georeference_is_reported():
    _, notes = build(single_road(f"<right>{lane(-1)}</right>"))
    assert any("no geoReference" in note for note in notes)


@pytest.mark.parametrize(
    ("text", "record", "reason"),
    [
        (
            single_road("<right>" + lane(-1, 'a="wide" b="0" c="0" d="0"') + "</right>"),
            "road id='7'",
            "a='wide' is not a number",
        ),
        (single_road("<right><lane type='driving'/></right>"), "road id='7'", "'id'"),
        (
            "<OpenDRIVE><road id='1' length='5'><lanes/></road></OpenDRIVE>",
            "road id='1'",
            "planView",
        ),
        (
            "<OpenDRIVE><road id='1' length='5'><planView><geometry s='0' x='0' y='0' hdg='0' "
            "length='5'><clothoid/></geometry></planView></road></OpenDRIVE>",
            "clothoid",
            "is not a line",
        ),
        ("<OpenDRIVE><road id='1'", "XML", "line 1, column 11"),
        ("<map/>", "XML", "not <OpenDRIVE>"),
        (
            single_road(f"<right>{lane(-1)}</right>").replace(
                '<header revMajor="1" revMinor="6"/>',
                "<header><geoReference>+proj=nowhere</geoReference></header>",
            ),
            "header geoReference",
            "unknown projection",
        ),
    ],
)
def test_malformed_elements_are_named(text, record, reason):
    with pytest.raises(MapRecordError) as caught:
        build(text)
    assert record in caught.value.record
    assert reason in caught.value.reason


def test_a_signal_in_two_controllers_is_refused():
    text = JUNCTION_XODR.read_text().replace(
        '<control signalId="TL1" type="0"/>', '<control signalId="TL2" type="0"/>'
    )
    with pytest.raises(MapRecordError, match="signal TL2 is already in controller 1"):
        build(text)


def signal_line(signal_id: str) -> str:
    return next(
        line for line in JUNCTION_XODR.read_text().splitlines() if f'id="{signal_id}"' in line
    )


def test_a_signal_reference_governs_the_referencing_road_too():
    reference = '<signalReference s="0" t="5" id="TL3" orientation="-"/>'
    lane_map, _ = build(JUNCTION_XODR.read_text().replace(signal_line("TL1"), reference))
    assert set(lane_map.traffic_lights["TL3"].lane_ids) == {"1_0_1", "3_0_1"}
    assert lane_map.lane("1_0_1").traffic_light_ids == ("TL3",)
    assert "TL1" not in lane_map.traffic_lights


def test_a_stop_line_at_a_connector_start_belongs_to_the_lane_before_it():
    text = JUNCTION_XODR.read_text().replace(signal_line("TL4"), "")
    on_connector = (
        '<signals><signal s="0.5" t="-3" id="TL4" dynamic="yes" orientation="+" '
        'type="1000001" subtype="-1"/></signals></road>'
    )
    head, tail = text.split('<road name="" length="20" id="10" junction="100">')
    tail = tail.replace("</road>", on_connector, 1)
    lane_map, _ = build(head + '<road name="" length="20" id="10" junction="100">' + tail)
    assert lane_map.traffic_lights["TL4"].lane_ids == ("4_0_1",)
    assert lane_map.lane("4_0_1").stop_line_s == pytest.approx(100.0)
    assert lane_map.lane("10_0_-1").stop_line_s is None


def test_validity_and_orientation_select_the_governed_lanes():
    signal = (
        '<signals><signal s="80" t="-9" id="S1" dynamic="yes" orientation="+" '
        'type="1000001" subtype="-1"><validity fromLane="-2" toLane="-2"/></signal></signals>'
    )
    lanes = f"<left>{lane(1)}</left><right>{lane(-1)}{lane(-2)}</right>"
    lane_map, notes = build(single_road(lanes).replace("</road>", signal + "</road>"))
    assert lane_map.traffic_lights["S1"].lane_ids == ("7_0_-2",)
    assert lane_map.lane("7_0_-2").stop_line_s == pytest.approx(80.0)
    assert lane_map.lane("7_0_-1").stop_line_s is None
    # A light in no controller runs as an intersection of its own.
    (site,) = lane_map.intersections.values()
    assert site.approach_groups == (("S1",),)
    assert any("S1 is in no controller" in note for note in notes)


def test_road_marks_become_the_markings_on_their_borders():
    width = 'a="3.5" b="0" c="0" d="0"'
    lanes = f"""
      <left><lane id="1" type="driving"><width sOffset="0" {width}/>
        <roadMark sOffset="0" type="solid" color="standard" width="0.12"/></lane></left>
      <center><lane id="0" type="none">
        <roadMark sOffset="0" type="solid solid" color="yellow" width="0.15"/>
        <roadMark sOffset="60" type="broken" color="yellow"/></lane></center>
      <right>
        <lane id="-1" type="driving"><width sOffset="0" {width}/>
          <roadMark sOffset="0" type="broken" color="white"/></lane>
        <lane id="-2" type="driving"><width sOffset="0" {width}/>
          <roadMark sOffset="0" type="botts dots" color="white"/></lane>
      </right>"""
    lane_map, notes = build(single_road(lanes))
    by_id = {m.id: m for m in lane_map.markings}
    assert set(by_id) == {"7_0_1_0", "7_0_0_0", "7_0_0_1", "7_0_-1_0"}
    centre, after = by_id["7_0_0_0"], by_id["7_0_0_1"]
    assert (centre.color, centre.lines, centre.width_m) == (
        MarkingColor.YELLOW,
        (LineStyle.SOLID, LineStyle.SOLID),
        0.15,
    )
    assert centre.points[:, 1] == pytest.approx(0.0)
    assert (centre.points[0, 0], centre.points[-1, 0]) == pytest.approx((0.0, 60.0))
    assert (after.lines, after.points[-1, 0]) == ((LineStyle.DASHED,), pytest.approx(100.0))
    # Borders: lane 1's outer edge at t = 3.5, lane -1's at t = -3.5, at the road's height.
    assert by_id["7_0_1_0"].points[:, 1] == pytest.approx(3.5)
    assert by_id["7_0_-1_0"].points[:, 1] == pytest.approx(-3.5)
    assert by_id["7_0_-1_0"].points[0, 2] == pytest.approx(2.0)
    assert any("botts dots" in note for note in notes)
