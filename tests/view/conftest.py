"""A simulator's insides for the view's tests: a world and its bridge context."""

from __future__ import annotations

from pathlib import Path

import pytest

from egosim.bridge import BridgeContext, simulation_context
from egosim.world import World
from egosim.world.map import build_builtin_map
from egosim.world.scenario import load_default_scenario

TOWN = build_builtin_map("town")
STRAIGHT = build_builtin_map("straight")


def context_of(world: World, data_root: Path | None = None) -> BridgeContext:
    roots = (data_root,) if data_root is not None else ()
    return simulation_context(world, data_roots=roots)


@pytest.fixture
def town(tmp_path: Path) -> BridgeContext:
    return context_of(World(TOWN, load_default_scenario()), tmp_path)


@pytest.fixture
def straight(tmp_path: Path) -> BridgeContext:
    return context_of(World(STRAIGHT), tmp_path)
