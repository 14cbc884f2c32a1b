"""NPC ghosts: NPCs placed from outside stand where they are told, and the world treats
them as NPCs (listed, collided with, followed)."""

import math

import pytest
from tests.world.traffic.scenes import EGO_OUT_OF_THE_WAY, run, world_from

from egosim.world.scenario import parse_scenario
from egosim.world.traffic.ghosts import GhostPlacement, TurnSignal
from egosim.world.vehicle import DEFAULT_EGO_MODEL, vehicle_model

LANE = "R1_E_1"
PARKED = 1.0e6  # start delay, s: an NPC that never sets off


def _straight(npcs: list[dict], ego: dict | None = None) -> dict:
    return {"map": "straight", "ego": ego or EGO_OUT_OF_THE_WAY, "npcs": npcs}


def _ghost(world, unique_id: int, s: float, speed: float = 0.0, **lamps) -> GhostPlacement:
    x, y, z, heading = world.map.pose_at(LANE, s)
    return GhostPlacement(
        unique_id, vehicle_model(DEFAULT_EGO_MODEL), (x, y, z), heading, speed, **lamps
    )


def _npc(world, unique_id: int):
    return next(n for n in world.object_list().npcs if n.unique_id == unique_id)


def test_a_listed_npc_stops_being_simulated_and_stands_where_it_is_told() -> None:
    world = world_from(_straight([{"start": {"lane": LANE, "s": 50.0}, "speed_mps": 10.0}]))
    npc_id = int(world.npcs.unique_ids[0])
    refused = world.place_npc_ghosts([_ghost(world, npc_id, 200.0, speed=5.0)])
    run(world, 2.0)
    assert refused == []
    assert len(world.npcs) == 0
    listing = world.object_list()
    assert listing.num_npcs == 1
    ghost = _npc(world, npc_id)
    assert ghost.position[:2] == pytest.approx(world.map.pose_at(LANE, 200.0)[:2])
    assert math.hypot(*ghost.velocity[:2]) == pytest.approx(5.0)


def test_an_unknown_id_spawns_an_npc_of_the_named_model() -> None:
    world = world_from(_straight([]))
    world.place_npc_ghosts([_ghost(world, 77, 100.0)])
    ghost = _npc(world, 77)
    model = vehicle_model(DEFAULT_EGO_MODEL)
    assert ghost.name == model.name
    assert ghost.size == pytest.approx((model.length, model.width, model.height))
    # Ids handed out later never clash with the ghost's.
    world.place_npc_ghosts([_ghost(world, 5, 150.0)])
    assert world.add_ego(DEFAULT_EGO_MODEL, world.egos[0].vehicle.status().pose).unique_id > 77


def test_acceleration_follows_the_speed_change_between_placements() -> None:
    world = world_from(_straight([]))
    world.place_npc_ghosts([_ghost(world, 9, 100.0, speed=10.0)])
    run(world, 0.5)
    world.place_npc_ghosts([_ghost(world, 9, 105.0, speed=12.0)])
    assert _npc(world, 9).acceleration[0] == pytest.approx(2.0 / 0.5)


def test_ids_of_egos_are_refused() -> None:
    world = world_from(_straight([]))
    ego_id = world.egos[0].unique_id
    assert world.place_npc_ghosts([_ghost(world, ego_id, 100.0)]) == [ego_id]
    assert len(world.npc_ghosts) == 0


def test_a_simulated_npc_stops_behind_a_ghost_on_its_lane() -> None:
    world = world_from(_straight([{"start": {"lane": LANE, "s": 20.0}, "speed_mps": 15.0}]))
    world.place_npc_ghosts([_ghost(world, 99, 150.0)])
    run(world, 40.0)
    npc_front = world.npcs.s[0] + world.npcs.dims[0, 0] / 2.0
    ghost_rear = 150.0 - world.npc_ghosts.get(99).model.length / 2.0
    assert world.npcs.speed[0] == pytest.approx(0.0, abs=1e-3)
    assert ghost_rear - world.npcs.idm.min_gap_m - 0.5 < npc_front < ghost_rear
    assert world.vehicle_collisions == []


def test_an_npc_ghost_placed_on_another_npc_collides_with_it() -> None:
    world = world_from(_straight([{"start": {"lane": LANE, "s": 100.0}, "start_delay_s": PARKED}]))
    parked_id = int(world.npcs.unique_ids[0])
    world.place_npc_ghosts([_ghost(world, 50, 90.0)])
    run(world, 0.1)
    world.place_npc_ghosts([_ghost(world, 50, 97.0)])
    run(world, 0.1)
    assert len(world.vehicle_collisions) == 1
    ids = {v.unique_id for v in world.vehicle_collisions[0].vehicles}
    assert ids == {parked_id, 50}


def test_the_ego_collides_with_a_ghost() -> None:
    world = world_from(_straight([], ego={"start": {"lane": LANE, "s": 50.0}}))
    s_ahead = 50.0 + world.egos[0].vehicle.model.length
    world.place_npc_ghosts([_ghost(world, 60, s_ahead + 10.0)])
    run(world, 0.1)
    world.place_npc_ghosts([_ghost(world, 60, s_ahead - 1.0)])
    run(world, 0.1)
    assert world.ego_collision_log[-1].other.unique_id == 60


def test_lamps_are_kept_per_ghost() -> None:
    world = world_from(_straight([]))
    world.place_npc_ghosts(
        [
            _ghost(world, 11, 100.0, turn_signal=TurnSignal.LEFT, brake_light=True),
            _ghost(world, 12, 140.0, turn_signal=TurnSignal.HAZARD),
        ]
    )
    world.place_npc_ghosts([_ghost(world, 11, 101.0, turn_signal=TurnSignal.RIGHT)])
    assert world.npc_ghosts.get(11).turn_signal == TurnSignal.RIGHT
    assert world.npc_ghosts.get(11).brake_light is False
    assert world.npc_ghosts.get(12).turn_signal == TurnSignal.HAZARD


def test_deleting_all_objects_removes_the_ghosts() -> None:
    world = world_from(_straight([]))
    world.place_npc_ghosts([_ghost(world, 13, 100.0)])
    world.load_scenario(parse_scenario(_straight([]), "reload"))
    assert len(world.npc_ghosts) == 0
    assert world.object_list().num_npcs == 0
