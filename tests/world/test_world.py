"""The World assembled: object list, lane quantities, determinism, the default scenario."""

import math

import numpy as np
import pytest

from egosim.world import World
from egosim.world.collision import Footprints, touching_pairs
from egosim.world.map import build_builtin_map
from egosim.world.scenario import load_default_scenario, parse_scenario
from egosim.world.traffic import ObjectType
from egosim.world.vehicle import ControlCommand, LongitudinalMode

STRAIGHT = build_builtin_map("straight")
TOWN = build_builtin_map("town")


def _crowd() -> World:
    """Ego at x = 100 m; 10 NPCs, 8 pedestrians and 7 obstacles scattered round it."""
    return World(
        STRAIGHT,
        parse_scenario(
            {
                "map": "straight",
                "ego": {"start": {"lane": "R1_E_1", "s": 100.0}},
                "npcs": [
                    {"start": {"lane": lane, "s": s}, "start_delay_s": 1e6}
                    for lane, s in (
                        ("R1_E_2", 60),
                        ("R1_W_1", 500),
                        ("R1_E_2", 200),
                        *(("R1_W_2", 100.0 * k) for k in range(1, 8)),
                    )
                ],
                "pedestrians": [
                    {"waypoints": [[20.0 * k, 15.0], [20.0 * k + 1, 15.0]], "loop": False}
                    for k in range(8)
                ],
                "obstacles": [{"pose": {"x": 37.0 * k, "y": -15.0}} for k in range(7)],
            },
            "crowd.yaml",
        ),
    )


def test_object_list_holds_the_closest_objects_split_by_kind() -> None:
    world = _crowd()
    world.step()
    listing = world.object_list(size=12)
    assert (listing.num_npcs, listing.num_pedestrians, listing.num_obstacles) == (10, 8, 7)
    objects = world.objects()
    others = objects.object_types != ObjectType.EGO
    # Measured from the ego's reported position (/Ego_topic), as a client measures it.
    pose = world.ego_status().pose
    ego_centre = np.array([pose.x, pose.y])
    distance = np.hypot(*(objects.positions[others, :2] - ego_centre).T)
    nearest = set(objects.unique_ids[others][np.argsort(distance)[:12]].tolist())
    listed = [*listing.npcs, *listing.pedestrians, *listing.obstacles]
    assert {o.unique_id for o in listed} == nearest
    for kind, group in (
        (ObjectType.NPC_VEHICLE, listing.npcs),
        (ObjectType.PEDESTRIAN, listing.pedestrians),
        (ObjectType.OBSTACLE, listing.obstacles),
    ):
        assert all(o.object_type == kind for o in group)
        ranges = [math.dist(o.position[:2], ego_centre) for o in group]
        assert ranges == sorted(ranges)


def test_object_list_is_capped_at_its_configured_size() -> None:
    world = _crowd()
    listing = world.object_list()
    assert len(listing.npcs) + len(listing.pedestrians) + len(listing.obstacles) == 20
    world.object_list_size = 40
    listing = world.object_list()
    assert len(listing.npcs) + len(listing.pedestrians) + len(listing.obstacles) == 25


def test_ego_lane_quantities_come_from_the_map() -> None:
    world = World(
        STRAIGHT,
        parse_scenario(
            {"map": "straight", "ego": {"start": {"lane": "R1_E_1", "s": 50.0, "lateral": 0.5}}},
            "lane.yaml",
        ),
    )
    state = world.ego_lane_state()
    assert state.lane_id == "R1_E_1"
    assert state.s == pytest.approx(50.0)
    assert state.lateral_offset == pytest.approx(0.5)
    assert state.cross_track_error == pytest.approx(-0.5)
    assert state.distance_left == pytest.approx(3.5 / 2 - 0.5)
    assert state.distance_right == pytest.approx(3.5 / 2 + 0.5)


def _drive_default_town(seconds: float) -> World:
    world = World(TOWN, load_default_scenario())
    for k in range(round(seconds / world.physics_step_s)):
        # A scripted ego: speed up, hold 8 m/s, steer a little left and right.
        steer = 0.02 * math.sin(0.5 * k * world.physics_step_s)
        world.egos[0].vehicle.command(
            ControlCommand(mode=LongitudinalMode.VELOCITY, velocity=8.0, front_steer=steer)
        )
        world.step()
    return world


def test_same_scenario_and_commands_give_bit_identical_worlds() -> None:
    first, second = _drive_default_town(20.0), _drive_default_town(20.0)
    a, b = first.objects(), second.objects()
    for field in ("unique_ids", "positions", "headings", "velocities", "accelerations"):
        assert np.array_equal(getattr(a, field), getattr(b, field)), field
    assert first.ego_status() == second.ego_status()
    assert first.signals.intersection_statuses() == second.signals.intersection_statuses()


def test_default_scenario_runs_a_minute_without_nan_or_npc_overlaps() -> None:
    world = World(TOWN, load_default_scenario())
    assert (len(world.npcs), len(world.pedestrians), len(world.obstacles)) == (8, 6, 4)
    start = world.npcs.pose[:, :2].copy()
    for _ in range(60):
        for _ in range(100):
            world.step()
        table = world.objects()
        assert np.all(np.isfinite(table.positions))
        assert np.all(np.isfinite(table.velocities))
        assert np.all(np.isfinite(table.accelerations))
        npcs = world.npcs.table()
        boxes = Footprints(npcs.positions[:, :2], npcs.headings, npcs.sizes[:, 0], npcs.sizes[:, 1])
        assert touching_pairs(boxes, boxes).size == 0
    assert world.sim_time == pytest.approx(60.0)
    assert world.vehicle_collisions == []
    moved = np.hypot(*(world.npcs.pose[:, :2] - start).T)
    assert np.count_nonzero(moved > 50.0) >= 5
    assert np.ptp(world.pedestrians.position, axis=0).max() > 0.0


def test_pedestrians_cross_only_when_the_crossed_road_is_red() -> None:
    world = World(
        TOWN,
        parse_scenario(
            {
                "map": "town",
                "ego": {"start": {"lane": "R26_E_1", "s": 50.0}},
                "pedestrians": [{"crosswalk": "CW6_E", "speed_mps": 1.5}],
            },
            "walk.yaml",
        ),
    )
    crosswalk = world.map.crosswalks["CW6_E"]
    world.signals.set_light("TL6_E", 16)
    for _ in range(500):
        world.step()
    assert world.pedestrians.position[0] == pytest.approx(crosswalk.start)
    world.signals.set_light("TL6_E", 1)
    for _ in range(500):
        world.step()
    walked = math.dist(world.pedestrians.position[0], crosswalk.start)
    assert walked == pytest.approx(5.0 * 1.5, abs=0.02)
