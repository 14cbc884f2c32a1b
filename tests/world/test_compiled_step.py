"""The compiled world step (world/kernels) against the numpy path: one busy scenario
through both gives bit-identical worlds at every step."""

from __future__ import annotations

import numpy as np
import pytest
from tests.compiled_paths import busy_town, drive

from egosim.world import World, kernels
from egosim.world.map import build_builtin_map
from egosim.world.scenario import parse_scenario

pytestmark = pytest.mark.skipif(
    not kernels.AVAILABLE, reason="no compiled path: numba missing or EGOSIM_COMPILED=0"
)

TOWN = build_builtin_map("town")
STEPS = 450


def snapshots(compiled: bool, monkeypatch: pytest.MonkeyPatch) -> tuple[list[bytes], set[str]]:
    """Every step's objects, ego status and collisions, as bytes; and what happened."""
    monkeypatch.setattr(kernels, "ACTIVE", compiled)
    world = World(TOWN, parse_scenario(busy_town(TOWN), "busy town"))
    taken = []
    seen = set()
    for k in range(STEPS):
        drive(world, k)
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
