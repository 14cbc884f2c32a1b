"""Shared set-up of the camera tests: the renderer, scenes and hand-made object tables."""

from __future__ import annotations

import functools

import numpy as np
import pytest

from egosim.render import open_renderer
from egosim.sensors.camera_scene import StaticScene, build_static_scene
from egosim.sensors.errors import RendererUnavailableError
from egosim.world.map import build_builtin_map
from egosim.world.traffic.objects import ObjectTable, ObjectType


@functools.cache
def _renderer_or_reason() -> object:
    try:
        return open_renderer()
    except RendererUnavailableError as error:
        return str(error)


def renderer() -> object:
    """The default renderer; the test is skipped, saying why, where none can run."""
    found = _renderer_or_reason()
    if isinstance(found, str):
        pytest.skip(f"no camera renderer: {found}")
    return found


@functools.cache
def scene_of(map_name: str) -> StaticScene:
    return build_static_scene(build_builtin_map(map_name))


def objects(
    *rows: tuple[int, ObjectType, tuple[float, float, float], float, tuple[float, ...]],
) -> ObjectTable:
    """A table of (unique_id, type, footprint centre, heading, size L W H) rows."""
    n = len(rows)
    return ObjectTable(
        unique_ids=np.array([r[0] for r in rows], dtype=np.int64),
        object_types=np.array([int(r[1]) for r in rows], dtype=np.int64),
        names=tuple("thing" for _ in rows),
        positions=np.array([r[2] for r in rows], dtype=np.float64).reshape(n, 3),
        headings=np.array([r[3] for r in rows], dtype=np.float64),
        velocities=np.zeros((n, 3)),
        accelerations=np.zeros((n, 3)),
        sizes=np.array([r[4] for r in rows], dtype=np.float64).reshape(n, 3),
    )
