"""NPCs on a loaded OpenDRIVE map route through its junction and obey its lights."""

from pathlib import Path

import pytest
from tests.world.traffic.scenes import run, world_from

from egosim.world import World
from egosim.world.map.opendrive import build_opendrive_map
from egosim.world.signals import GREEN, RED

JUNCTION_XODR = Path(__file__).parents[3] / "data" / "maps" / "junction.xodr"
# From the south arm, left across the junction into the west arm.
ROUTE = ["4_0_1", "14_0_-1", "3_0_-1"]


def world_with_npc() -> World:
    lane_map = build_opendrive_map("junction", JUNCTION_XODR.read_text(), [])
    scenario = {
        "map": "junction",
        "ego": {"start": {"lane": "1_0_-1", "s": 90.0}},
        "npcs": [{"start": {"lane": "4_0_1", "s": 20.0}, "speed_mps": 10.0, "route": ROUTE}],
    }
    return world_from(scenario, lane_map)


def test_npc_waits_on_red_then_turns_along_its_route():
    world = world_with_npc()
    world.signals.set_light("TL4", RED)
    run(world, 30.0)
    assert world.map.lane_ids[world.npcs.lane[0]] == "4_0_1"
    assert world.npcs.speed[0] == pytest.approx(0.0, abs=1e-3)
    front = world.npcs.s[0] + world.npcs.dims[0, 0] / 2.0
    assert front <= world.map.lane("4_0_1").stop_line_s

    world.signals.set_light("TL4", GREEN)
    run(world, 20.0)
    assert world.map.lane_ids[world.npcs.lane[0]] in ("14_0_-1", "3_0_-1")


def test_the_junction_runs_a_phase_program_over_its_controllers():
    world = world_with_npc()
    seen = set()
    for _ in range(round(90.0 / world.physics_step_s)):
        world.step()
        north, south = (world.signals.light(i).aspect for i in ("TL2", "TL4"))
        east, west = (world.signals.light(i).aspect for i in ("TL1", "TL3"))
        # One controller's heads switch together; the two controllers never both go.
        assert north == south
        assert not (north & GREEN and (east | west) & GREEN)
        seen.add((bool(north & GREEN), bool(east & GREEN)))
    assert {(True, False), (False, True)} <= seen
