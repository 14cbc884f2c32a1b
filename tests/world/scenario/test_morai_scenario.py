"""MORAI SIM scenario files onto the world: axes, angles, units, placements, activation,
lights, frames, the report of what is not carried out, and errors without tracebacks."""

from __future__ import annotations

import math

import pytest
from tests import morai_scenarios as morai

from egosim.maps import load_map
from egosim.world import World
from egosim.world.scenario import LaneStart, PoseStart, ScenarioError
from egosim.world.scenario.morai import heading_of, read_morai_scenario, unity_to_enu
from egosim.world.vehicle import ControlCommand, Gear, LongitudinalMode

DT = 0.02


def read(document: dict, label: str = "scenario.json"):  # type: ignore[no-untyped-def]
    return read_morai_scenario(morai.text(document), label)


def world_of(document: dict, map_name: str = "straight") -> World:
    return World(load_map(map_name), read(document).scenario)


def hold(world: World, speed: float) -> None:
    world.egos[0].vehicle.command(ControlCommand(mode=LongitudinalMode.VELOCITY, velocity=speed))


# -- axes, angles, units ---------------------------------------------------------------


def test_a_unity_point_lands_on_its_enu_point() -> None:
    # Unity: x = -east, y = up, z = -north.
    assert unity_to_enu(-12.5, 3.0, 40.0) == (12.5, -40.0, 3.0)


@pytest.mark.parametrize(
    ("yaw_deg", "heading"),
    [
        (0.0, 0.0),
        (90.0, math.pi / 2),
        (-29.315, math.radians(-29.315)),
        (190.0, -math.radians(170.0)),
    ],
)
def test_rot_degrees_give_the_heading_counter_clockwise_from_east(
    yaw_deg: float, heading: float
) -> None:
    assert heading_of(yaw_deg) == pytest.approx(heading)


def test_the_ego_stands_at_pos_facing_yaw_at_its_speed_in_its_gear() -> None:
    document = morai.scenario(
        "straight", morai.ego(morai.at_pose(100.0, -1.75, 0.0), gear=1, kmh=36.0)
    )
    spec = read(document).scenario.ego
    assert spec is not None and spec.start == PoseStart(100.0, -1.75, 0.0, 0.0)
    assert spec.speed == pytest.approx(10.0)  # 36 km/h
    world = World(load_map("straight"), read(document).scenario)
    status = world.ego_status()
    assert (status.pose.x, status.pose.y, status.pose.yaw) == pytest.approx((100.0, -1.75, 0.0))
    assert status.velocity[0] == pytest.approx(10.0)
    assert world.egos[0].vehicle.gear is Gear.PARKING


def test_rotations_written_as_text_with_thousands_separators_read_as_numbers() -> None:
    entry = morai.ego(morai.at_pose(0.0, 0.0, 0.0))
    entry["initPosition"]["rot"]["yaw"] = "-1,170.000"  # -1170 deg = -90 deg
    spec = read(morai.scenario("straight", entry)).scenario.ego
    assert spec is not None and isinstance(spec.start, PoseStart)
    assert spec.start.heading == pytest.approx(-math.pi / 2)


def test_init_link_ratio_one_half_places_the_ego_mid_link() -> None:
    document = morai.scenario("mgeo_sample", morai.ego(morai.on_link("R1_W_1", 0.5)))
    scenario = read(document).scenario
    assert scenario.ego is not None and scenario.ego.start == LaneStart("R1_W_1", ratio=0.5)
    world = World(load_map("mgeo_sample"), scenario)
    lane_map = world.map
    length = float(lane_map.lane_lengths[lane_map.lane_index("R1_W_1")])
    status = world.ego_status()
    # R1_W_1 runs west along y = 1.75 from x = 120.
    assert (status.pose.x, status.pose.y) == pytest.approx((120.0 - length / 2.0, 1.75))
    assert status.pose.yaw == pytest.approx(math.pi)
    assert world.ego_lane_state().lane_id == "R1_W_1"


# -- NPC vehicles ----------------------------------------------------------------------


def test_npc_models_by_data_id_and_desired_speed_by_km_h_or_share_of_the_limit() -> None:
    document = morai.scenario(
        "straight",
        vehicles=(
            morai.npc(morai.at_pose(50.0, -1.75, 0.0), 1, data_id=30100010, desired_kmh=54.0),
            morai.npc(
                morai.on_link("R1_E_2", 0.1), 2, data_id=30200003, desired_kmh=50, velocity_type=1
            ),
        ),
    )
    first, second = read(document).scenario.npcs
    assert (first.model, first.target_speed) == ("2016_Hyundai_Ioniq", pytest.approx(15.0))
    assert (second.model, second.target_speed, second.speed_factor) == (
        "2016_Kia_Niro(HEV)",
        None,
        0.5,
    )
    world = world_of(document)
    for _ in range(int(40.0 / DT)):
        world.step(DT)
    limit = 100.0 / 3.6
    assert world.npcs.speed[0] == pytest.approx(15.0, abs=0.2)
    assert world.npcs.speed[1] == pytest.approx(0.5 * limit, abs=0.3)


def test_an_npc_waits_until_the_ego_comes_within_its_active_distance() -> None:
    document = morai.scenario(
        "straight",
        morai.ego(morai.at_pose(100.0, -1.75, 0.0)),
        vehicles=(morai.npc(morai.at_pose(200.0, -1.75, 0.0), 7, kmh=20.0, active_distance=40.0),),
    )
    world = world_of(document)
    start = float(world.npcs.pose[0, 0])
    woke_at = None
    while world.sim_time < 12.0:
        hold(world, 10.0)
        world.step(DT)
        moved = world.npcs.pose[0, 0] - start > 1e-9
        if moved and woke_at is None:
            woke_at = world.ego_status().pose.x
        if woke_at is None:
            assert world.npcs.speed[0] == 0.0
    # It stands while the ego is farther than 40 m and sets off the step it is not.
    assert woke_at is not None
    assert start - woke_at == pytest.approx(40.0, abs=0.5)


def test_lane_change_and_closed_loop_requests_are_reported_once_each() -> None:
    vehicles = tuple(
        morai.npc(morai.at_pose(50.0 + 20 * k, -1.75, 0.0), k, isLaneChange=True, bias=0.2)
        for k in range(3)
    )
    notes = read(morai.scenario("straight", vehicles=vehicles)).notes
    lane_change = [n for n in notes if "vehicleList[].isLaneChange" in n]
    assert len(lane_change) == 1
    assert "(vehicleList[0], vehicleList[1], vehicleList[2])" in lane_change[0]
    assert sum("vehicleList[].bias" in n for n in notes) == 1
    assert not any("isCloseLoop" in n for n in notes)  # false asks for nothing


# -- pedestrians -----------------------------------------------------------------------


def test_a_waypoint_path_in_unity_axes_is_walked_in_enu_at_its_speed() -> None:
    document = morai.scenario(
        "straight",
        morai.ego(morai.at_pose(10.0, -1.75, 0.0)),
        pedestrians=(morai.pedestrian(60.0, 9.0, -90.0, 3, kmh=3.6, waypoints=True),),
        paths=(morai.path(3, (60.0, 9.0), (60.0, -9.0)),),
    )
    walker = read(document).scenario.pedestrians[0]
    assert walker.waypoints == ((60.0, 9.0), (60.0, -9.0))
    assert walker.speed == pytest.approx(1.0)  # 3.6 km/h
    world = world_of(document)
    for _ in range(int(5.0 / DT)):
        world.step(DT)
    assert world.pedestrians.position[0] == pytest.approx((60.0, 4.0), abs=1e-6)
    assert world.pedestrians.heading[0] == pytest.approx(-math.pi / 2)


def test_a_pedestrian_walks_moving_distance_along_its_heading_and_loops_back() -> None:
    document = morai.scenario(
        "straight",
        pedestrians=(morai.pedestrian(30.0, 5.0, 180.0, 4, kmh=7.2, moving_m=6.0, loop=True),),
    )
    waypoints = read(document).scenario.pedestrians[0].waypoints
    assert waypoints is not None
    assert [pytest.approx(point) for point in waypoints] == [(30.0, 5.0), (24.0, 5.0)]
    world = world_of(document)
    for _ in range(int(4.0 / DT)):  # 8 m at 2 m/s: to the far end (6 m) and 2 m back
        world.step(DT)
    assert world.pedestrians.position[0] == pytest.approx((26.0, 5.0), abs=1e-6)


def test_a_pedestrian_waits_for_the_ego_within_its_active_distance_of_its_standard_point() -> None:
    document = morai.scenario(
        "straight",
        morai.ego(morai.at_pose(0.0, -1.75, 0.0)),
        pedestrians=(
            morai.pedestrian(
                80.0, 9.0, -90.0, 5, kmh=3.6, active_distance=30.0, standard=(80.0, -1.75)
            ),
        ),
    )
    world = world_of(document)
    woke_at = None
    while world.sim_time < 10.0:
        hold(world, 10.0)
        world.step(DT)
        if woke_at is None and world.pedestrians.position[0, 1] < 9.0:
            woke_at = world.ego_status().pose.x
    assert woke_at is not None
    assert 80.0 - woke_at == pytest.approx(30.0, abs=0.25)


def test_a_pedestrian_that_is_not_active_walks_at_once() -> None:
    entry = morai.pedestrian(80.0, 9.0, -90.0, 5, active_distance=1.0)
    entry["active"] = False
    world = world_of(morai.scenario("straight", pedestrians=(entry,)))
    world.step(DT)
    assert world.pedestrians.position[0, 1] < 9.0


# -- objects ---------------------------------------------------------------------------


def test_objects_by_data_id_with_their_scale_and_heading() -> None:
    document = morai.scenario(
        "straight",
        objects=(
            morai.thing(40.0, 6.0, 90.0, 11, 40100005),  # traffic cone
            morai.thing(44.0, 6.0, 0.0, 12, 40100004, scale=2.0),  # barrel
            morai.thing(48.0, 6.0, 0.0, 13, 40100013),  # parked Sonata
            morai.thing(52.0, 6.0, 0.0, 14, 49999999),  # unknown
        ),
    )
    read_scenario = read(document)
    cone, barrel, car = read_scenario.scenario.obstacles
    assert (cone.model, cone.size) == ("Cone", pytest.approx((0.40, 0.40, 0.70)))
    assert cone.pose.heading == pytest.approx(math.pi / 2)
    assert (barrel.model, barrel.size) == ("Drum", pytest.approx((1.2, 1.2, 1.8)))
    assert car.model == "2019_Hyundai_Sonata"
    assert any("objectList[].DataID: 49999999" in note for note in read_scenario.notes)
    world = world_of(document)
    assert len(world.obstacles) == 3


def test_a_scale_stretches_length_width_and_height_along_unitys_axes() -> None:
    entry = morai.thing(40.0, 6.0, 0.0, 11, 40100001)
    entry["scale"] = morai.vector(2.0, 3.0, 4.0)  # Unity: x across, y up, z along
    (box,) = read(morai.scenario("straight", objects=(entry,))).scenario.obstacles
    assert box.size == pytest.approx((4.0, 2.0, 3.0))


# -- traffic lights, map and frames ----------------------------------------------------


def test_tl_list_starts_each_intersection_in_its_phase_and_time() -> None:
    document = morai.scenario("mgeo_sample", lights=({"index": 0, "state": 2, "deltaTime": 1.5},))
    world = World(load_map("mgeo_sample"), read(document).scenario)
    status = world.signals.intersection_status(1)
    assert (status.phase_index, status.elapsed_s) == (2, pytest.approx(1.5))


def test_a_tl_list_entry_the_map_does_not_have_names_its_json_path() -> None:
    document = morai.scenario(
        "mgeo_sample",
        lights=({"index": 0, "state": 0, "deltaTime": 0.0}, {"index": 3, "state": 0}),
    )
    with pytest.raises(ScenarioError) as caught:
        World(load_map("mgeo_sample"), read(document).scenario)
    assert str(caught.value).startswith("scenario.json: tlList[1]: no signalised intersection")


def test_map_info_names_the_map_and_its_offsets_frame_the_positions() -> None:
    scenario = read(morai.scenario("R_KR_PG_K-City")).scenario
    assert (scenario.map_name, scenario.map_reference) == ("R_KR_PG_K-City", "R_KR_PG_K-City")
    assert scenario.origin is not None
    assert (scenario.origin.utm_zone, scenario.origin.northern) == (52, True)
    assert (scenario.origin.origin_east, scenario.origin.origin_north) == morai.TOWN_ORIGIN


def test_positions_measured_from_other_offsets_move_into_the_maps_frame() -> None:
    # The file's frame sits 100 m east and 20 m north of the map's: its (0, -21.75) is the
    # map's (100, -1.75), the inner eastbound lane.
    east, north = morai.TOWN_ORIGIN
    document = morai.scenario(
        "straight",
        morai.ego(morai.at_pose(0.0, -21.75, 0.0)),
        objects=(morai.thing(10.0, -20.0, 0.0, 11, 40100005),),
        origin=(east + 100.0, north + 20.0),
    )
    world = World(load_map("straight"))
    report = world.load_scenario(read(document).scenario)
    status = world.ego_status()
    assert (status.pose.x, status.pose.y) == pytest.approx((100.0, -1.75), abs=1e-6)
    assert status.pose.yaw == pytest.approx(0.0, abs=1e-9)
    assert world.obstacles.table().positions[0, :2] == pytest.approx((110.0, 0.0), abs=1e-6)
    assert len(report.notes) == 1 and "moved into the map's frame" in report.notes[0]


def test_a_link_the_map_does_not_have_is_refused_naming_the_file_s_field() -> None:
    document = morai.scenario(
        "mgeo_sample", vehicles=(morai.npc(morai.on_link("A2256W000001", 0.5), 1),)
    )
    world = World(load_map("mgeo_sample"))
    with pytest.raises(ScenarioError) as caught:
        world.load_scenario(read(document).scenario)
    assert str(caught.value) == (
        "scenario.json: vehicleList[0].initPosition.initLink: "
        "no lane 'A2256W000001' in map 'mgeo_sample'"
    )
    assert len(world.npcs) == 0


def test_a_scenario_for_another_map_is_refused() -> None:
    with pytest.raises(ScenarioError, match="scenario is for map 'town'"):
        world_of(morai.scenario("town"))


# -- the report and the errors ---------------------------------------------------------


def test_every_field_not_carried_out_is_reported_once_by_name() -> None:
    document = morai.scenario(
        "straight",
        morai.ego(morai.at_pose(10.0, -1.75, 0.0)),
        pedestrians=tuple(morai.pedestrian(20.0 + k, 9.0, -90.0, k, anim={}) for k in range(7)),
    )
    document["spawnPointList"] = [{"DataID": 0}]
    document["egoVehicle"]["currentControlMode"] = 1
    document["futureField"] = True
    notes = read(document).notes
    assert sum("pedestrianList[].anim:" in n for n in notes) == 1
    assert any(n.endswith("pedestrianList[4] and 2 more)") for n in notes if "[].anim" in n)
    assert "scenario.json: spawnPointList: not carried out: spawn points make no NPCs" in notes[-2]
    assert any(n.startswith("scenario.json: egoVehicle.currentControlMode:") for n in notes)
    assert "scenario.json: futureField: not a field egosim knows; not read" in notes
    names = [n.split(": ")[1] for n in notes]
    assert len(names) == len(set(names))


def test_json_syntax_errors_name_the_line() -> None:
    text = morai.text(morai.scenario("straight")).replace('"vehicleList": []', '"vehicleList": [,]')
    line = text[: text.index("[,]")].count("\n") + 1
    with pytest.raises(ScenarioError) as caught:
        read_morai_scenario(text, "bad.json")
    assert caught.value.line == line
    assert str(caught.value).startswith(f"bad.json:{line}: column ")


def test_semantic_errors_name_each_json_path_at_once() -> None:
    vehicles = [morai.npc(morai.at_pose(10.0 * k, 0.0, 0.0), k) for k in range(3)]
    vehicles[2]["DataID"] = "sonata"
    vehicles[1]["initPosition"]["rot"]["yaw"] = "north"
    document = morai.scenario("straight", vehicles=tuple(vehicles))
    document["objectList"] = [morai.thing(0.0, 0.0, 0.0, 1, 40100005)]
    document["objectList"][0]["scale"] = morai.vector(1.0, 0.0, 1.0)
    with pytest.raises(ScenarioError) as caught:
        read(document)
    lines = str(caught.value).splitlines()
    assert "scenario.json: vehicleList[2].DataID: 'sonata' is not an integer" in lines
    assert "scenario.json: vehicleList[1].initPosition.rot.yaw: 'north' is not a number" in lines
    assert any(line.startswith("scenario.json: objectList[0].scale:") for line in lines)


@pytest.mark.parametrize(
    "document",
    [
        "[]",
        "null",
        '{"mapInfo": 3}',
        '{"mapInfo": {"mapName": ""}}',
        '{"mapInfo": {"mapName": "straight"}, "vehicleList": {"a": 1}}',
        '{"mapInfo": {"mapName": "straight"}, "vehicleList": [7, {"initPosition": []}]}',
        '{"mapInfo": {"mapName": "straight"}, "egoVehicle": {"DataID": 1, "initPosition": {}}}',
        '{"mapInfo": {"mapName": "straight", "eastOffset": 1, "northOffset": 2, '
        '"globalCoordinateSystem": "no such grid"}}',
        '{"mapInfo": {"mapName": "straight"}, "tlList": [{"index": -1, "state": true}]}',
        '{"mapInfo": {"mapName": "straight"}, "waypointDataList": [{"waypointData": [1]}]}',
        '{"mapInfo": {"mapName": "straight"}, "pedestrianList": [{"pos": {"x": 1e999}}]}',
        "[" * 100000,
        b"\xff\xfe{",
    ],
)
def test_malformed_files_are_scenario_errors_never_tracebacks(document: str | bytes) -> None:
    with pytest.raises(ScenarioError):
        read_morai_scenario(document, "bad.json")


def test_a_file_with_only_a_map_loads_and_keeps_the_ego() -> None:
    world = World(load_map("straight"))
    before = world.ego_status().pose
    report = world.load_scenario(read(morai.scenario("straight")).scenario)
    assert not report.ego_placed and world.ego_status().pose == before
    assert len(world.npcs) == 0


def test_paths_no_pedestrian_walks_and_walkers_without_a_path_are_reported() -> None:
    document = morai.scenario(
        "straight",
        pedestrians=(
            morai.pedestrian(60.0, 9.0, -90.0, 3, waypoints=True),
            morai.pedestrian(70.0, 9.0, -90.0, 4, waypoints=True, moving_m=4.0),
        ),
        paths=(
            {"pathName": "ObstaclePath - 8", "waypointData": []},
            morai.path(3, (60.0, 9.0), (60.0, -9.0)),
        ),
    )
    read_scenario = read(document)
    assert read_scenario.scenario.pedestrians[1].waypoints == ((70.0, 9.0), (70.0, 5.0))
    notes = read_scenario.notes
    assert any(
        n.startswith("scenario.json: waypointDataList[].pathName: a path no pedestrian walks")
        and n.endswith("(waypointDataList[0])")
        for n in notes
    )
    assert any(
        "pedestrianList[].isWaypointMode: no waypointDataList path" in n
        and n.endswith("(pedestrianList[1])")
        for n in notes
    )
