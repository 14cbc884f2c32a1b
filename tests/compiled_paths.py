"""A busy scenario for comparing the compiled world step (world/kernels) with the numpy
path: every kernel has work to do in it."""

from __future__ import annotations

import math
from typing import Any

from egosim.world import World
from egosim.world.map import LaneMap
from egosim.world.vehicle import ControlCommand, LongitudinalMode

NPC_SPACING_M = 35.0


def busy_town(lane_map: LaneMap) -> dict[str, Any]:
    """NPCs on every road lane (some changing lanes, some scripted or late), pedestrians
    on the crosswalks and sidewalks, and obstacles on the ego's lane ahead of it."""
    roads = [lane for lane in lane_map.lanes.values() if not lane.is_junction]
    npcs: list[dict[str, Any]] = []
    for k, lane in enumerate(roads):
        for slot in range(int((lane.length - 20.0) // NPC_SPACING_M)):
            npc: dict[str, Any] = {"start": {"lane": lane.id, "s": 10.0 + slot * NPC_SPACING_M}}
            if lane.id == "R5_E_1" and slot < 3:
                continue  # the ego's lane: its obstacles, then the NPCs it runs into
            if slot == 0 and lane.left_neighbor is not None and k % 3 == 0:
                npc["lane_change"] = {"lane": lane.left_neighbor, "after_s": 1.0 + k % 4}
            if (k + slot) % 5 == 0:
                npc["target_speed_mps"] = 6.0
            if (k + slot) % 7 == 0:
                npc["start_delay_s"] = 2.0
            npcs.append(npc)
    walkers: list[dict[str, Any]] = [{"crosswalk": c} for c in lane_map.crosswalks]
    walkers += [{"sidewalk": s, "start_s": 5.0} for s in lane_map.sidewalks]
    ahead = [lane_map.pose_at("R5_E_1", s) for s in (30.0, 38.0, 46.0)]
    return {
        "map": lane_map.name,
        "seed": 7,
        # Short phases: every light goes through yellow within the run.
        "signals": {"default": {"green_s": 3.0, "left_s": 2.0, "yellow_s": 2.0}},
        "ego": {"start": {"lane": "R5_E_1", "s": 5.0}, "speed_mps": 10.0},
        "npcs": npcs,
        "pedestrians": walkers,
        "obstacles": [
            {"model": model, "pose": {"x": x, "y": y}}
            for model, (x, y, _, _) in zip(("Cone", "Drum", "Barrier"), ahead, strict=True)
        ],
    }


def drive(world: World, step: int) -> None:
    """The ego's command at `step`: 12 m/s ahead, weaving a little (it runs into the
    obstacles on its lane after about 2 s)."""
    steer = 0.004 * math.sin(0.3 * step * world.physics_step_s)
    world.egos[0].vehicle.command(
        ControlCommand(mode=LongitudinalMode.VELOCITY, velocity=12.0, front_steer=steer)
    )
