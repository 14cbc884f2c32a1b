"""Oriented-box collisions: the SAT, swept checks, and the records the World keeps."""

import math

import numpy as np
import pytest
from tests.world.traffic.scenes import EGO_OUT_OF_THE_WAY, run, world_from

from egosim.world.collision import Footprints, touching_pairs
from egosim.world.contact import RESTITUTION
from egosim.world.traffic import ObjectType
from egosim.world.vehicle import ControlCommand

CAR_LENGTH_M, CAR_WIDTH_M = 4.5, 1.8
PARKED = 1.0e6  # start delay, s: an NPC that never sets off


def _cars(centres: list[tuple[float, float]], headings: list[float]) -> Footprints:
    n = len(centres)
    return Footprints(
        np.array(centres, dtype=np.float64),
        np.array(headings, dtype=np.float64),
        np.full(n, CAR_LENGTH_M),
        np.full(n, CAR_WIDTH_M),
    )


def test_separating_axis_tells_diagonal_neighbours_apart() -> None:
    # Two cars at 45 deg, side by side along their width: their bounding boxes overlap,
    # the cars themselves are 0.2 m apart (or 0.2 m into each other).
    normal = np.array([-math.sin(math.pi / 4), math.cos(math.pi / 4)])
    for spacing, touching in ((CAR_WIDTH_M + 0.2, False), (CAR_WIDTH_M - 0.2, True)):
        other = tuple(spacing * normal)
        boxes = _cars([(0.0, 0.0), other], [math.pi / 4, math.pi / 4])
        assert touching_pairs(boxes, boxes).tolist() == ([[0, 1]] if touching else [])


def test_head_on_at_highway_speed_does_not_tunnel() -> None:
    # Nose to nose 0.5 m apart, each at 50 m/s for a 0.1 s step: they swap places and
    # are 0.5 m apart, tail to tail, after it, having passed through each other.
    before = _cars([(0.0, 0.0), (5.0, 0.0)], [0.0, math.pi])
    after = _cars([(5.0, 0.0), (0.0, 0.0)], [0.0, math.pi])
    assert touching_pairs(before, before).size == 0
    assert touching_pairs(after, after).size == 0
    assert touching_pairs(before, after).tolist() == [[0, 1]]


def test_many_boxes_pair_only_the_touching_ones() -> None:
    # A row of cars 5 m apart (0.5 m gaps) with one more car on top of the third.
    centres = [(5.0 * k, 0.0) for k in range(50)] + [(10.0, 0.5)]
    boxes = _cars(centres, [0.0] * 51)
    assert touching_pairs(boxes, boxes).tolist() == [[2, 50]]


def _ego_behind_parked_npc() -> dict:
    return {
        "map": "straight",
        "ego": {"start": {"lane": "R1_E_1", "s": 20.0}},
        "npcs": [{"start": {"lane": "R1_E_1", "s": 100.0}, "start_delay_s": PARKED}],
    }


def test_ego_running_into_an_npc_is_recorded_once() -> None:
    world = world_from(_ego_behind_parked_npc())
    npc_id = int(world.npcs.unique_ids[0])
    for _ in range(3000):
        run(world, 0.01, ego_speed_mps=8.0)
        if world.ego_collision_log:
            break
    assert len(world.ego_collision_log) == 1
    record = world.ego_collision_log[0]
    assert record.ego_id == world.egos[0].unique_id
    assert record.other.unique_id == npc_id
    assert record.other.object_type == ObjectType.NPC_VEHICLE
    assert record.other.position == pytest.approx(tuple(world.npcs.pose[0, :3]))
    # The parked car is immovable: the ego bounces back with the restitution's share of
    # its speed (it was halted on the spot before contacts were solid).
    assert world.ego_status().velocity[0] == pytest.approx(-RESTITUTION * 8.0, rel=0.02)
    assert world.ego_collision() == record
    # Braking after the bounce: still the one contact.
    world.egos[0].vehicle.command(ControlCommand(brake=1.0))
    run(world, 3.0)
    assert world.ego_collision_log == [record]


def test_npcs_crashing_into_each_other_leave_one_vehicle_collision() -> None:
    # The second NPC drives in lane 2 but 3.5 m to its left, i.e. down lane 1 where the
    # first one is parked; it does not see it as its leader and hits it.
    world = world_from(
        {
            "map": "straight",
            "ego": EGO_OUT_OF_THE_WAY,
            "npcs": [
                {"start": {"lane": "R1_E_1", "s": 200.0}, "start_delay_s": PARKED},
                {"start": {"lane": "R1_E_2", "s": 100.0, "lateral": 3.5}, "speed_mps": 10.0},
            ],
        }
    )
    run(world, 30.0)
    assert len(world.vehicle_collisions) == 1
    crash = world.vehicle_collisions[0]
    assert {v.unique_id for v in crash.vehicles} == set(world.npcs.unique_ids.tolist())
    assert all(v.object_type == ObjectType.NPC_VEHICLE for v in crash.vehicles)
    assert world.npcs.crashed.all()
    assert np.all(world.npcs.speed == 0.0)
    assert world.ego_collision_log == []


def test_head_on_crash_at_highway_speed_is_caught_with_a_long_step() -> None:
    highway = 120.0 / 3.6
    world = world_from(
        {
            "map": "straight",
            "ego": {"start": {"lane": "R1_E_1", "s": 100.0}, "speed_mps": highway},
            # Westbound, 3.5 m to its left: in the ego's lane, coming the other way.
            "npcs": [
                {
                    "start": {"lane": "R1_W_1", "s": 600.0, "lateral": 3.5},
                    "speed_mps": highway,
                    "target_speed_mps": highway,
                }
            ],
        },
        physics_step_s=0.15,
    )
    run(world, 12.0, ego_speed_mps=highway)
    assert len(world.ego_collision_log) == 1
    assert world.ego_collision_log[0].other.unique_id == int(world.npcs.unique_ids[0])
