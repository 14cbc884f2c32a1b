"""ObjectStatusList lists each kind closest first, by the distance a client computes from
the two messages: /Ego_topic's position to each ObjectStatus.position."""

from __future__ import annotations

import math
from typing import Any

from egosim.bridge import HANDLERS, simulation_context
from egosim.world import World
from egosim.world.map import build_builtin_map
from egosim.world.scenario import parse_scenario
from tests.e2e.scenarios import OBJECTS_FORE_AND_AFT


def decoded(context: Any, key: str, type_name: str) -> Any:
    """The row's message as a subscriber reads it: serialised, then deserialised."""
    message_type = context.profile.message(type_name)
    message = HANDLERS.publishers[key](context, context.row(key))
    return message_type.deserialize(message_type.serialize(message))


def order_from(origin: tuple[float, float], listed: list[Any]) -> list[int]:
    return [
        o.unique_id
        for o in sorted(listed, key=lambda o: math.dist(origin, (o.position.x, o.position.y)))
    ]


def test_each_list_is_ordered_by_distance_from_the_reported_ego_position() -> None:
    world = World(build_builtin_map("straight"), parse_scenario(OBJECTS_FORE_AND_AFT))
    context = simulation_context(world)
    context.tick(0.01)
    ego = decoded(context, "ego_status", "morai_msgs/EgoVehicleStatus")
    objects = decoded(context, "object_status", "morai_msgs/ObjectStatusList")
    reported = (ego.position.x, ego.position.y)
    heading = math.radians(ego.heading)
    ahead = world.egos[0].vehicle.model.box_centre_ahead_of_reference
    box_centre = (reported[0] + ahead * math.cos(heading), reported[1] + ahead * math.sin(heading))
    for listed in (objects.npc_list, objects.obstacle_list):
        ids = [o.unique_id for o in listed]
        assert ids == order_from(reported, listed)
        # The scene tells the two apart: from the footprint centre every pair swaps.
        assert ids != order_from(box_centre, listed)
    assert len(objects.obstacle_list) == 4
    assert len(objects.npc_list) == 2
