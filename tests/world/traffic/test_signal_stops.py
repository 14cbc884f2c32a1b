"""NPCs at stop lines: red stops them before the line, green lets them go, yellow
stops those that comfortably can."""

import pytest
from tests.world.traffic.scenes import run, world_from

from egosim.world.signals import GREEN, RED, YELLOW

# R5_E_1 runs east from junction 6 to junction 7, whose light TL7_W governs it.
APPROACH, LIGHT = "R5_E_1", "TL7_W"
# The ego waits far away on the ring.
TOWN_EGO_OUT_OF_THE_WAY = {"start": {"lane": "R26_E_1", "s": 50.0}}


def _approaching_npc(s: float, speed: float = 0.0) -> dict:
    return {
        "map": "town",
        "ego": TOWN_EGO_OUT_OF_THE_WAY,
        "npcs": [
            {
                "start": {"lane": APPROACH, "s": s},
                "speed_mps": speed,
                "route": [APPROACH, "R6_E_1"],
            }
        ],
    }


def _front_bumper(world) -> float:
    return float(world.npcs.s[0] + world.npcs.dims[0, 0] / 2.0)


def test_npc_stops_before_the_stop_line_on_red_and_goes_on_green() -> None:
    world = world_from(_approaching_npc(10.0))
    stop_line = world.map.lanes[APPROACH].stop_line_s
    world.signals.set_light(LIGHT, RED)
    run(world, 40.0)
    assert world.map.lane_ids[world.npcs.lane[0]] == APPROACH
    assert world.npcs.speed[0] == pytest.approx(0.0, abs=1e-3)
    assert stop_line - world.npcs.idm.min_gap_m - 0.5 < _front_bumper(world) <= stop_line

    world.signals.set_light(LIGHT, GREEN)
    run(world, 15.0)
    assert world.map.lane_ids[world.npcs.lane[0]] != APPROACH


def test_yellow_stops_an_npc_that_can_stop_comfortably() -> None:
    world = world_from(_approaching_npc(10.0, speed=12.0))
    stop_line = world.map.lanes[APPROACH].stop_line_s
    world.signals.set_light(LIGHT, YELLOW)
    run(world, 30.0)
    assert world.npcs.speed[0] == pytest.approx(0.0, abs=1e-3)
    assert _front_bumper(world) <= stop_line


def test_yellow_it_cannot_stop_for_is_passed_even_when_it_turns_red() -> None:
    world = world_from(_approaching_npc(120.0, speed=13.0))
    stop_line = world.map.lanes[APPROACH].stop_line_s
    distance = stop_line - _front_bumper(world)
    assert distance < 13.0**2 / (2.0 * world.npcs.idm.comfortable_decel_mps2)
    world.signals.set_light(LIGHT, YELLOW)
    run(world, 0.5)
    world.signals.set_light(LIGHT, RED)
    run(world, 5.0)
    assert world.map.lane_ids[world.npcs.lane[0]] != APPROACH
