"""The scenarios of examples/scenarios/: each loads, runs, and does what its comment says."""

from __future__ import annotations

import itertools
import math
from pathlib import Path

import numpy as np
import pytest

from egosim.maps import load_map, scenario_map_location
from egosim.scenario_files import read_scenario_file
from egosim.world import World
from egosim.world.scenario import parse_scenario
from egosim.world.signals import GREEN, RED, YELLOW
from egosim.world.traffic import ObjectType
from egosim.world.vehicle import ControlCommand, LongitudinalMode
from egosim.world.vehicle.skid_steer_commands import BodyVelocityCommand

GALLERY = Path(__file__).parents[1] / "examples" / "scenarios"


def gallery_world(name: str, suffix: str = ".yaml") -> World:
    path = GALLERY / f"{name}{suffix}"
    if suffix == ".yaml":
        scenario = parse_scenario(path.read_text("utf-8"), str(path))
    else:
        scenario = read_scenario_file(path)
    return World(load_map(scenario_map_location(scenario.map_reference, GALLERY)), scenario)


def hold_speed(world: World, speed: float) -> None:
    world.egos[0].vehicle.command(ControlCommand(mode=LongitudinalMode.VELOCITY, velocity=speed))


def test_every_gallery_file_is_tested() -> None:
    tested = {name[len("test_") :] for name in globals() if name.startswith("test_")}
    assert {p.stem for p in (*GALLERY.glob("*.yaml"), *GALLERY.glob("*.json"))} <= tested


def test_every_gallery_file_says_what_it_tests() -> None:
    for path in GALLERY.glob("*.yaml"):
        lines = path.read_text("utf-8").splitlines()
        assert lines[0].startswith("# "), path.name
        assert any(line.startswith("# Checks: ") for line in lines), path.name


def test_cut_in() -> None:
    world = gallery_world("cut_in")
    ego_lane = world.ego_lane_state().lane_id
    lanes, gaps = [], []
    while world.sim_time < 6.0:
        hold_speed(world, 20.0)
        world.step(0.02)
        lanes.append(world.map.lane_ids[world.npcs.lane[0]])
        gaps.append(world.npcs.pose[0, 0] - world.ego_status().pose.x)
    enters = lanes.index(ego_lane)
    assert lanes[0] == "R1_E_2"
    assert 1.9 <= enters * 0.02 <= 2.1
    # It moves in ahead of the ego, closer than 30 m (centre to reference point).
    assert 5.0 < gaps[enters] < 30.0
    assert set(lanes[enters:]) == {ego_lane}
    # By the end it drives on the ego lane's centreline, ahead of the ego.
    ego_y = world.map.pose_at(ego_lane, 0.0)[1]
    assert world.npcs.pose[0, 1] == pytest.approx(ego_y, abs=0.01)
    assert gaps[-1] > 0
    assert world.ego_collision() is None


def test_pedestrian_crosswalk() -> None:
    world = gallery_world("pedestrian_crosswalk")
    lane_y = world.ego_status().pose.y
    walker = world.objects().object_types == int(ObjectType.PEDESTRIAN)
    road_half_width = 2 * 3.5
    onto_ego_lane = None
    while world.sim_time < 40.0:
        world.step(0.1)
        y = float(world.objects().positions[walker][0, 1])
        light = world.ego_traffic_light()
        assert light is not None and light.light_id == "TL1_W"
        if light.aspect & GREEN:
            assert y > road_half_width  # waiting on the kerb
        if onto_ego_lane is None and abs(y - lane_y) < 1.75:
            onto_ego_lane = world.sim_time
            assert light.aspect == RED
    assert onto_ego_lane is not None and 15.0 < onto_ego_lane < 30.0


def test_red_light() -> None:
    world = gallery_world("red_light")
    lane = world.map.lanes[world.ego_lane_state().lane_id]
    assert lane.stop_line_s is not None
    model = world.egos[0].vehicle.model
    front = model.length / 2 + model.bounding_box_center_offset  # reference point to bumper
    seen = []
    while world.ego_lane_state().s + front < lane.stop_line_s:
        hold_speed(world, 11.1)
        world.step(0.02)
        light = world.ego_traffic_light()
        assert light is not None
        seen.append((round(world.sim_time, 2), light.aspect))
        assert world.sim_time < 15.0, "the ego never reached the stop line"
    assert (light.light_id,) == lane.traffic_light_ids == ("TL1_W",)
    assert light.aspect == RED
    assert 8.0 < world.sim_time < 10.0
    aspects = dict(seen)
    assert aspects[1.0] & GREEN and aspects[4.0] == YELLOW and aspects[7.0] == RED


def test_stalled_car() -> None:
    world = gallery_world("stalled_car")
    stalled = world.npcs.pose[0].copy()
    for _ in range(40 * 20):
        world.step(0.05)
    assert np.array_equal(world.npcs.pose[0], stalled)
    lane_ids = [world.map.lane_ids[k] for k in world.npcs.lane]
    assert lane_ids[0] == world.ego_lane_state().lane_id == "R1_E_1"
    # The NPC behind it has stopped short of it; the next lane's NPC has gone past.
    queued_gap = (
        world.npcs.s[0] - world.npcs.s[1] - (world.npcs.dims[0, 0] + world.npcs.dims[1, 0]) / 2
    )
    assert lane_ids[1] == "R1_E_1" and 0.5 < queued_gap < 5.0
    assert world.npcs.speed[1] < 0.01
    assert lane_ids[2] == "R1_E_2" and world.npcs.pose[2, 0] > stalled[0] + 100
    assert world.vehicle_collisions == []


def test_dense_junction() -> None:
    world = gallery_world("dense_junction")
    centre = np.array(world.map.intersections[7].center)
    near, crossed = [], set()
    for k in range(90 * 20):
        world.step(0.05)
        lanes = [world.map.lane_ids[i] for i in world.npcs.lane]
        crossed |= {
            int(uid)
            for uid, lane in zip(world.npcs.unique_ids, lanes, strict=True)
            if lane.startswith("J7_")
        }
        if k % 20 == 0:
            distance = np.hypot(*(world.npcs.pose[:, :2] - centre).T)
            near.append(int(np.sum(distance < 80.0)))
    assert len(world.npcs) == 24
    assert np.median(near) >= 12
    assert len(crossed) >= 16
    assert world.vehicle_collisions == []
    assert world.ego_collision() is None


COURSE = [(15.0, 0.0), (22.0, 0.0), (25.0, 1.2), (31.0, -1.2), (37.0, 1.2), (43.0, -1.2),
          (47.0, 0.0), (53.0, 0.0)]  # fmt: skip


def drive_robot(world: World, waypoints: list[tuple[float, float]]) -> None:
    """A pure-pursuit skid-steer driver: 1 m/s, steering towards a point 1.5 m ahead."""
    path = np.array(waypoints)
    dense = np.vstack([np.linspace(a, b, 50) for a, b in itertools.pairwise(path)])
    robot = world.egos[0].vehicle
    while world.sim_time < 90.0 and world.ego_collision() is None:
        pose = robot.status().pose
        if pose.x >= waypoints[-1][0] - 1.0:
            return
        ahead = np.hypot(dense[:, 0] - pose.x, dense[:, 1] - pose.y)
        nearest = int(np.argmin(ahead))
        target = dense[min(nearest + np.searchsorted(ahead[nearest:] >= 1.5, True), len(dense) - 1)]
        bearing = math.atan2(target[1] - pose.y, target[0] - pose.x) - pose.yaw
        bearing = math.remainder(bearing, math.tau)
        robot.command(BodyVelocityCommand(linear=1.0, angular=2.0 * bearing))
        world.step(0.02)


def test_robot_obstacle_course() -> None:
    world = gallery_world("robot_obstacle_course")
    assert world.egos[0].vehicle.model.name == "WeBOT_Indoor_Robot"
    assert len(world.obstacles) == 13
    drive_robot(world, COURSE)
    assert world.ego_collision() is None
    assert world.ego_status().pose.x >= COURSE[-1][0] - 1.0


def test_robot_obstacle_course_blocks_a_straight_run() -> None:
    # The cones really are in the way: straight down the aisle the robot hits one.
    world = gallery_world("robot_obstacle_course")
    drive_robot(world, [(15.0, 0.0), (53.0, 0.0)])
    collision = world.ego_collision()
    assert collision is not None and collision.other.name == "Cone"


def test_morai_jaywalker() -> None:
    world = gallery_world("morai_jaywalker", ".json")
    assert world.ego_lane_state().lane_id == "R1_W_1"
    assert world.ego_status().pose.x == pytest.approx(120.0 - 0.1 * 100.5)
    ioniq, niro = (world.npcs.names.index(n) for n in ("2016_Hyundai_Ioniq", "2016_Kia_Niro(HEV)"))
    # The Niro drives at once, towards 60 % of its lane's limit.
    assert world.npcs.speed_factor[niro] == pytest.approx(0.6)
    woke_at = walked_at = None
    fastest = 0.0
    while world.sim_time < 16.0:
        hold_speed(world, 5.0)
        world.step(0.02)
        fastest = max(fastest, float(world.npcs.speed[ioniq]))
        ego_x = world.ego_status().pose.x
        if woke_at is None and world.npcs.speed[ioniq] > 0.0:
            woke_at = ego_x
        if walked_at is None and world.pedestrians.position[0, 1] < 9.0:
            walked_at = ego_x
        if world.sim_time == pytest.approx(1.0):
            assert world.npcs.speed[niro] > 1.0
    # The Ioniq stood until the ego came within 25 m, then drove off towards 30 km/h.
    assert woke_at is not None and woke_at - 75.0 == pytest.approx(25.0, abs=0.3)
    assert 8.0 < fastest <= 30 / 3.6 + 1e-9
    # The pedestrian set off when the ego came within 20 m of the lane's centre at x = 45,
    # and crosses southwards at 4 km/h.
    assert walked_at is not None and walked_at - 45.0 == pytest.approx(20.0, abs=0.3)
    assert world.pedestrians.velocity[0] == pytest.approx((0.0, -4.0 / 3.6))
    sizes = sorted(tuple(s) for s in world.obstacles.table().sizes)
    assert sizes == [pytest.approx((0.4, 0.4, 0.7))] * 2 + [pytest.approx((0.9, 0.9, 1.35))]
    assert not world.ego_collision_log
