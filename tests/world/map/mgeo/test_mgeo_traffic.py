"""NPCs on a loaded MGeo map route through its junction and obey its lights."""

import pytest
from tests.world.map.mgeo.sample_mgeo import mgeo_files
from tests.world.traffic.scenes import run, world_from

from egosim.world import World
from egosim.world.map.mgeo import build_mgeo_map
from egosim.world.signals import GREEN, RED, YELLOW

ROUTE = ["L_S_in", "C_SN", "L_N_out"]


def world_with_npc_on(lane: str, s: float) -> World:
    lane_map = build_mgeo_map("sample", mgeo_files(), [])
    scenario = {
        "map": "sample",
        "ego": {"start": {"lane": "L_E_out", "s": 90.0}},
        "npcs": [{"start": {"lane": lane, "s": s}, "speed_mps": 10.0, "route": ROUTE}],
    }
    return world_from(scenario, lane_map)


def npc_lane(world: World) -> str:
    return world.map.lane_ids[world.npcs.lane[0]]


def test_npc_waits_at_the_stop_line_on_red_and_follows_its_route_on_green():
    world = world_with_npc_on("L_S_in", 10.0)
    world.signals.set_light("TL_S", RED)
    run(world, 30.0)
    assert npc_lane(world) == "L_S_in"
    assert world.npcs.speed[0] == pytest.approx(0.0, abs=1e-3)
    front = world.npcs.s[0] + world.npcs.dims[0, 0] / 2.0
    assert front <= world.map.lane("L_S_in").stop_line_s

    world.signals.set_light("TL_S", GREEN)
    run(world, 20.0)
    assert npc_lane(world) in ("C_SN", "L_N_out", "L_N_curve")


def test_npc_crosses_the_stop_line_only_on_a_go_aspect_of_the_phase_program():
    world = world_with_npc_on("L_S_in", 60.0)
    crossed_on = None
    for _ in range(round(120.0 / world.physics_step_s)):
        before = npc_lane(world)
        aspect = world.signals.light("TL_S").aspect
        world.step()
        if before == "L_S_in" and npc_lane(world) != "L_S_in":
            crossed_on = aspect
            break
    assert crossed_on is not None
    assert crossed_on & (GREEN | YELLOW)
    assert npc_lane(world) == "C_SN"
