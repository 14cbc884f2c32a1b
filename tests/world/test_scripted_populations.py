"""A storyboard's entities as populations of the world: listed after the world's own of
their kind, immovable, never stepped, and in lanes where the storyboard says."""

from __future__ import annotations

import numpy as np
import pytest

from egosim.world import World
from egosim.world.map import build_builtin_map
from egosim.world.populations import ScriptedPopulation, ScriptedRoadUsers, place_on_lanes
from egosim.world.scenario import parse_scenario
from egosim.world.traffic import ObjectType
from egosim.world.traffic.scripted import ScriptedObject, ScriptedObjects
from egosim.world.vehicle import ControlCommand, LongitudinalMode

STRAIGHT = build_builtin_map("straight")
EAST_1 = STRAIGHT.lane_index("R1_E_1")
CAR = (4.5, 1.8, 1.5)


def placed(
    uid: int,
    kind: ObjectType,
    x: float,
    speed: float = 0.0,
    lane: tuple[int, float] | None = None,
    y: float = -1.75,
) -> ScriptedObject:
    size = CAR if kind == ObjectType.NPC_VEHICLE else (0.6, 0.6, 1.8)
    return ScriptedObject(uid, kind, "m", (x, y, 0.0), 0.0, (speed, 0.0), (0.0, 0.0), size, lane)


def test_road_users_stand_where_the_storyboard_says_or_where_they_project() -> None:
    scripted = ScriptedObjects()
    scripted.place(
        [
            # Said to be 5 m further along its lane than its box: the storyboard's word holds.
            placed(1, ObjectType.NPC_VEHICLE, 100.0, speed=8.0, lane=(EAST_1, 105.0)),
            placed(2, ObjectType.NPC_VEHICLE, 300.0, speed=6.0),  # projected
            placed(3, ObjectType.NPC_VEHICLE, 500.0, y=20.0),  # off the road: in no lane
            placed(4, ObjectType.PEDESTRIAN, 200.0),
            placed(5, ObjectType.OBSTACLE, 250.0),  # objects stand in no lane
        ]
    )
    cars = ScriptedRoadUsers(scripted, ObjectType.NPC_VEHICLE)
    walkers = ScriptedRoadUsers(scripted, ObjectType.PEDESTRIAN)
    things = ScriptedPopulation(scripted, ObjectType.OBSTACLE)
    car_lanes, walker_lanes, thing_lanes = place_on_lanes(STRAIGHT, [cars, walkers, things])
    assert cars.table().unique_ids.tolist() == [1, 2, 3]
    assert car_lanes.lane.tolist() == [EAST_1, EAST_1]
    assert car_lanes.s.tolist() == pytest.approx([105.0, 300.0])
    assert car_lanes.half_length.tolist() == [CAR[0] / 2.0] * 2
    assert car_lanes.speed.tolist() == pytest.approx([8.0, 6.0])
    assert walker_lanes.s.tolist() == pytest.approx([200.0])
    assert len(thing_lanes.lane) == 0
    for population in (cars, walkers, things):
        assert not population.inverse_masses().any()  # immovable: the storyboard's motion


def test_npcs_stop_behind_a_scripted_car_which_the_world_never_moves() -> None:
    world = World(
        STRAIGHT,
        parse_scenario(
            {
                "map": "straight",
                "ego": {"start": {"lane": "R1_W_1", "s": 10.0}},
                "npcs": [{"start": {"lane": "R1_E_1", "s": 60.0}, "speed_mps": 10.0}],
                "obstacles": [{"model": "Cone", "pose": {"x": 400.0, "y": 5.0}}],
            },
            "scripted",
        ),
    )
    own_npc = int(world.npcs.unique_ids[0])
    world.scripted.place(
        [
            placed(90, ObjectType.NPC_VEHICLE, 200.0, lane=(EAST_1, 200.0)),
            placed(91, ObjectType.PEDESTRIAN, 300.0, y=10.0),
            placed(92, ObjectType.OBSTACLE, 350.0, y=10.0),
        ]
    )
    main = world.egos[0]
    world.scripted_egos.add(main.unique_id)
    ego_before = main.vehicle.status().pose
    before = world.objects()
    for _ in range(3000):  # 30 s
        main.vehicle.command(ControlCommand(mode=LongitudinalMode.VELOCITY, velocity=10.0))
        world.step()
    npcs, walkers, things = world.shown_tables()
    assert npcs.unique_ids.tolist() == [own_npc, 90]  # after the world's own, each kind
    assert walkers.unique_ids.tolist() == [91]
    assert things.unique_ids.tolist()[-1] == 92
    after = world.objects()
    scripted = np.isin(after.unique_ids, [90, 91, 92])
    assert after.positions[scripted].tolist() == before.positions[scripted].tolist()
    assert main.vehicle.status().pose == ego_before  # the storyboard places this ego
    front = world.npcs.pose[0, 0] + world.npcs.dims[0, 0] / 2.0
    assert world.npcs.speed[0] < 0.05
    assert 200.0 - CAR[0] / 2.0 - 3.0 < front < 200.0 - CAR[0] / 2.0  # a gap behind it
    assert world.vehicle_collisions == []
