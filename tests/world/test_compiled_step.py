"""The compiled world step (world/kernels) against the numpy path: one busy scenario
through both gives bit-identical worlds at every step."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest

from egosim.world import World, kernels
from egosim.world.map import LaneMap, build_builtin_map
from egosim.world.scenario import parse_scenario
from egosim.world.vehicle import ControlCommand, LongitudinalMode

pytestmark = pytest.mark.skipif(not kernels.AVAILABLE, reason="numba is not installed")

TOWN = build_builtin_map("town")
STEPS = 600
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
        "ego": {"start": {"lane": "R5_E_1", "s": 5.0}},
        "npcs": npcs,
        "pedestrians": walkers,
        "obstacles": [
            {"model": model, "pose": {"x": x, "y": y}}
            for model, (x, y, _, _) in zip(("Cone", "Drum", "Barrier"), ahead, strict=True)
        ],
    }


def snapshots(compiled: bool, monkeypatch: pytest.MonkeyPatch) -> tuple[list[bytes], set[str]]:
    """Every step's objects, ego status and collisions, as bytes; and what happened."""
    monkeypatch.setattr(kernels, "ACTIVE", compiled)
    world = World(TOWN, parse_scenario(busy_town(TOWN), "busy town"))
    taken = []
    seen = set()
    for k in range(STEPS):
        steer = 0.004 * math.sin(0.3 * k * world.physics_step_s)
        world.egos[0].vehicle.command(
            ControlCommand(mode=LongitudinalMode.VELOCITY, velocity=12.0, front_steer=steer)
        )
        world.step()
        table = world.objects()
        status = world.ego_status()
        fields = ("unique_ids", "positions", "headings", "velocities", "accelerations", "sizes")
        taken.append(
            b"".join(np.ascontiguousarray(getattr(table, field)).tobytes() for field in fields)
            + repr((status, world.ego_lane_state(), world.ego_collision_log)).encode()
            + repr(world.vehicle_collisions).encode()
        )
        npcs = world.npcs
        seen |= {
            name
            for name, happened in (
                ("a yellow latched", bool(npcs.yellow.any())),
                ("a lane change", bool(np.isfinite(npcs.slide_elapsed).any())),
                ("a queue", bool((npcs.speed[npcs.delay == 0.0] < 0.5).any())),
                ("an ego collision", bool(world.ego_collision_log)),
                ("an NPC collision", bool(world.vehicle_collisions)),
                ("a lasting ego contact", bool(world.ego_contacts)),
            )
            if happened
        }
    return taken, seen


def test_compiled_and_numpy_steps_give_bit_identical_worlds(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # Floats compared by repr (exact: the shortest string that reads back as the same
    # double), whether they are Python's or numpy's.
    np.set_printoptions(legacy="1.25")
    try:
        compiled, seen = snapshots(True, monkeypatch)
        plain, _ = snapshots(False, monkeypatch)
    finally:
        np.set_printoptions(legacy=False)
    assert len(seen) == 6, f"the scenario never had all of its events, only {sorted(seen)}"
    first_difference = next(
        (k for k, (a, b) in enumerate(zip(compiled, plain, strict=True)) if a != b), None
    )
    assert first_difference is None, f"the paths part at step {first_difference + 1}"
