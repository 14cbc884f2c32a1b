"""/Ego_topic and /Object_topic through the compiled world step and the numpy path: the
same scenario gives byte-identical messages at every tick."""

from __future__ import annotations

import pytest

from egosim.bridge import HANDLERS, simulation_context
from egosim.world import World, kernels
from egosim.world.map import build_builtin_map
from egosim.world.scenario import parse_scenario
from tests.compiled_paths import busy_town, drive

pytestmark = pytest.mark.skipif(
    not kernels.AVAILABLE, reason="no compiled path: numba missing or EGOSIM_COMPILED=0"
)

TICKS = 300
ROWS = {"ego_status": "morai_msgs/EgoVehicleStatus", "object_status": "morai_msgs/ObjectStatusList"}


def published(compiled: bool, monkeypatch: pytest.MonkeyPatch) -> list[bytes]:
    """Each tick's serialised /Ego_topic and /Object_topic."""
    monkeypatch.setattr(kernels, "ACTIVE", compiled)
    town = build_builtin_map("town")
    world = World(town, parse_scenario(busy_town(town), "busy town"))
    context = simulation_context(world)
    messages = []
    for k in range(TICKS):
        drive(world, k)
        context.tick(world.physics_step_s)
        for key, type_name in ROWS.items():
            message = HANDLERS.publishers[key](context, context.row(key))
            messages.append(context.profile.message(type_name).serialize(message))
    assert world.ego_collision_log, "the ego never ran into its obstacles"
    return messages


def test_compiled_and_numpy_steps_publish_identical_bytes(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    compiled = published(True, monkeypatch)
    plain = published(False, monkeypatch)
    differing = [k for k, (a, b) in enumerate(zip(compiled, plain, strict=True)) if a != b]
    assert not differing, f"{len(differing)} messages differ, first at tick {differing[0] // 2}"
    assert len(set(compiled)) > TICKS  # the messages change as the town moves
