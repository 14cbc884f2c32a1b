"""Several egos see each other: each is a vehicle in the others' object lists."""

from __future__ import annotations

from egosim.world import World
from egosim.world.map import build_builtin_map
from egosim.world.traffic import ObjectType
from egosim.world.vehicle import Pose


def test_each_ego_lists_the_others_as_vehicles() -> None:
    world = World(build_builtin_map("straight"))
    second = world.add_ego("2016_Kia_Niro(HEV)", Pose(x=60.0, y=-1.75))
    first_view = world.object_list(0)
    second_view = world.object_list(1)
    assert first_view.num_npcs == second_view.num_npcs == 1
    assert [o.unique_id for o in first_view.npcs] == [second.unique_id]
    assert [o.unique_id for o in second_view.npcs] == [world.egos[0].unique_id]
    assert {o.object_type for o in first_view.npcs} == {ObjectType.EGO}
    assert first_view.npcs[0].position[0] > 55.0
