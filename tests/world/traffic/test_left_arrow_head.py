"""A red / yellow / left-arrow head (type 1, the town's TL18_N over a T-junction stem
whose inner lane only turns left and outer lane only turns right): it never shows a
round green, and both of its movements go on its arrow and wait on its red."""

import pytest
from tests.world.traffic.scenes import run, world_from

from egosim.world.signals import GREEN, GREEN_LEFT, RED

LIGHT = "TL18_N"
LEFT_LANE, RIGHT_LANE = "R29_S_1", "R29_S_2"
TOWN_EGO_OUT_OF_THE_WAY = {"start": {"lane": "R26_E_1", "s": 50.0}}


def _stem_npcs() -> dict:
    return {
        "map": "town",
        "ego": TOWN_EGO_OUT_OF_THE_WAY,
        "npcs": [
            {"start": {"lane": LEFT_LANE, "s": 40.0}, "route": [LEFT_LANE, "R42_E_1"]},
            {"start": {"lane": RIGHT_LANE, "s": 40.0}, "route": [RIGHT_LANE, "R41_W_2"]},
        ],
    }


def test_its_program_lights_only_red_yellow_and_the_arrow() -> None:
    world = world_from(_stem_npcs())
    index = world.signals.light_ids.index(LIGHT)
    seen = set()
    for _ in range(round(120.0 / 0.1)):
        world.signals.step(0.1)
        seen.add(int(world.signals.aspects()[index]))
    assert GREEN_LEFT in seen
    assert not any(aspect & GREEN for aspect in seen if aspect > 0)


def test_left_and_right_turners_wait_on_red_and_go_on_the_arrow() -> None:
    world = world_from(_stem_npcs())
    world.signals.set_light(LIGHT, RED)
    run(world, 30.0)
    lanes = [world.map.lane_ids[k] for k in world.npcs.lane]
    assert lanes == [LEFT_LANE, RIGHT_LANE]
    assert world.npcs.speed == pytest.approx(0.0, abs=1e-3)
    world.signals.set_light(LIGHT, GREEN_LEFT)
    run(world, 10.0)
    left, right = (world.map.lane_ids[k] for k in world.npcs.lane)
    assert left in ("J18_N_E_left_1", "R42_E_1")
    assert right in ("J18_N_W_right_1", "R41_W_2")
