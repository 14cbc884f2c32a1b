"""Drivers treat a pedestrian in or about to step into their lane as a stopped obstacle."""

import numpy as np
from tests.world.traffic.scenes import EGO_OUT_OF_THE_WAY, world_from

from egosim.world.collision import Footprints, touching_pairs


def test_npc_waits_for_a_pedestrian_crossing_its_lane_then_drives_on() -> None:
    # The pedestrian is crossing the NPC's lane (R1_E_1, y from -3.5 to 0 m) at x = 300 m
    # very slowly; the NPC comes along at 10 m/s and gets there after 15 s.
    world = world_from(
        {
            "map": "straight",
            "ego": EGO_OUT_OF_THE_WAY,
            "npcs": [{"start": {"lane": "R1_E_1", "s": 150.0}, "speed_mps": 10.0}],
            "pedestrians": [
                {"waypoints": [[300.0, -2.5], [300.0, 12.0]], "speed_mps": 0.1, "loop": False}
            ],
        }
    )
    for _ in range(6000):
        world.step()
        npc, walker = world.npcs.table(), world.pedestrians.table()
        boxes = Footprints(
            np.vstack((npc.positions[:, :2], walker.positions[:, :2])),
            np.concatenate((npc.headings, walker.headings)),
            np.concatenate((npc.sizes[:, 0], walker.sizes[:, 0])),
            np.concatenate((npc.sizes[:, 1], walker.sizes[:, 1])),
        )
        assert touching_pairs(boxes, boxes).size == 0
    assert world.pedestrians.position[0, 1] > 1.0
    assert world.npcs.pose[0, 0] > 320.0
