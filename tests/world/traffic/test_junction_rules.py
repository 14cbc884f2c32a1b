"""Right of way inside junctions the lights do not protect."""

import itertools

from tests.world.traffic.scenes import run, world_from

from egosim.world.map import build_builtin_map
from egosim.world.signals import LightType
from egosim.world.traffic.junction_rules import junction_conflicts

TOWN = build_builtin_map("town")
# Junction 17 is a T on the ring whose heads flash yellow: nobody is held by a light.
FLASHING_JUNCTION = 17


def _approach_lanes(light_id: str) -> list[str]:
    return [lane.id for lane in TOWN.lanes.values() if light_id in lane.traffic_light_ids]


def _merging_movements() -> tuple[list[str], list[str]]:
    """Two routes from different arms of junction 17 into the same exit lane."""
    north, west = _approach_lanes("TL17_N"), _approach_lanes("TL17_W")
    for a, b in itertools.product(north, west):
        for ca, cb in itertools.product(TOWN.lanes[a].successors, TOWN.lanes[b].successors):
            shared = set(TOWN.lanes[ca].successors) & set(TOWN.lanes[cb].successors)
            if shared:
                exit_lane = shared.pop()
                return [a, ca, exit_lane], [b, cb, exit_lane]
    raise AssertionError("no merging movements at junction 17")


def test_merging_junction_lanes_conflict() -> None:
    first, second = _merging_movements()
    conflicts = junction_conflicts(TOWN)
    assert TOWN.lane_index(second[1]) in conflicts[TOWN.lane_index(first[1])]
    assert TOWN.lane_index(first[1]) in conflicts[TOWN.lane_index(second[1])]


def test_npcs_arriving_together_at_a_flashing_junction_take_turns() -> None:
    assert all(
        TOWN.traffic_lights[i].light_type == LightType.FLASHING_YELLOW
        for i in TOWN.intersections[FLASHING_JUNCTION].light_ids
    )
    routes = _merging_movements()
    world = world_from(
        {
            "map": "town",
            "ego": {"start": {"lane": "R5_E_1", "s": 30.0}},
            "npcs": [
                {
                    "start": {"lane": route[0], "s": TOWN.lanes[route[0]].length - 40.0},
                    "speed_mps": 8.0,
                    "target_speed_mps": 8.0,
                    "route": route,
                }
                for route in routes
            ],
        }
    )
    run(world, 30.0)
    assert world.vehicle_collisions == []
    exits = {world.map.lane_ids[k] for k in world.npcs.lane}
    assert exits.isdisjoint({routes[0][0], routes[1][0], routes[0][1], routes[1][1]})
