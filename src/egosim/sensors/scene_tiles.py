"""The static scene cut into ground tiles at two levels of detail, so a renderer draws
only what a camera can see, and far tiles cheaply.

Triangles are grouped by the tile under their centre; each tile keeps a vertex range
per level and the box around its triangles. A tile whose box lies wholly beyond one
plane of the view frustum cannot cover a pixel and is skipped, which leaves the image
as it was. A tile whose nearest point is far enough that COARSE_TOLERANCE_M projects to
less than MAX_ERROR_PX is drawn coarse: strips simplified to that tolerance, paint
narrower than it left out (as a game engine's texture filtering fades such lines into
the asphalt). Most of a town's triangles are far away and a few pixels tall, and a
software rasteriser pays for each triangle however small.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from egosim.sensors.camera import boxes_in_view
from egosim.sensors.camera_mesh import Detail
from egosim.world.arrays import FloatArray, IntArray

TILE_SIZE_M = 40.0
COARSE_TOLERANCE_M = 0.25
MAX_ERROR_PX = 0.5

_LEVELS = (Detail.FINE, Detail.COARSE)


@dataclass(frozen=True, eq=False)
class SceneTiles:
    """Tile k at level l (0 fine, 1 coarse) is vertices first[k, l] : first[k, l] +
    count[k, l] of its mesh; all its triangles lie inside the box lower[k]..upper[k]
    (scene frame). Each level's tiles follow each other without gaps."""

    first: IntArray
    count: IntArray
    lower: FloatArray
    upper: FloatArray


def tile_order(
    positions: npt.NDArray[np.float32] | FloatArray,
    details: IntArray,
    size_m: float = TILE_SIZE_M,
) -> tuple[IntArray, SceneTiles]:
    """The vertex order that stores a triangle list's (3 N, 3) `positions` as the fine
    level's tiles, then the coarse level's, and those tiles; `details` (N,) are the
    triangles' Detail values (a triangle of both levels is stored twice).

    Triangles wider than a tile (the terrain) form a tile of their own; within a tile,
    triangles keep their order, so equal depths resolve as before."""
    triangles = positions.reshape(-1, 3, 3).astype(np.float64)
    lower, upper = triangles.min(axis=1), triangles.max(axis=1)
    cells = np.floor((lower[:, :2] + upper[:, :2]) / (2.0 * size_m)).astype(np.int64)
    wide = np.any(upper[:, :2] - lower[:, :2] > size_m, axis=1)
    cells[wide] = np.iinfo(np.int64).min
    keys, tile_of = np.unique(cells, axis=0, return_inverse=True)
    tile_of = tile_of.reshape(-1)
    tiles = len(keys)

    by_tile = np.argsort(tile_of, kind="stable")
    starts = np.concatenate(([0], np.cumsum(np.bincount(tile_of, minlength=tiles))[:-1]))
    first = np.zeros((tiles, 2), np.int64)
    count = np.zeros((tiles, 2), np.int64)
    order, stored = [], 0
    for level, detail in enumerate(_LEVELS):
        members = by_tile[(details[by_tile] & detail.value) != 0]
        sizes = np.bincount(tile_of[members], minlength=tiles)
        first[:, level] = 3 * (stored + np.concatenate(([0], np.cumsum(sizes)[:-1])))
        count[:, level] = 3 * sizes
        order.append(members)
        stored += len(members)
    kept = np.concatenate(order)
    vertex_order = (3 * kept[:, None] + np.arange(3)).reshape(-1)
    return vertex_order, SceneTiles(
        first=first,
        count=count,
        lower=np.minimum.reduceat(lower[by_tile], starts),
        upper=np.maximum.reduceat(upper[by_tile], starts),
    )


def coarse_beyond_m(focal_px: float) -> float:
    """The distance beyond which COARSE_TOLERANCE_M looks smaller than MAX_ERROR_PX
    through a lens of focal length `focal_px` (pixels)."""
    return focal_px * COARSE_TOLERANCE_M / MAX_ERROR_PX


def visible_ranges(
    tiles: SceneTiles, clip_from_scene: FloatArray, eye: FloatArray, focal_px: float
) -> list[tuple[int, int]]:
    """(first vertex, vertex count) of each run of tiles that may show in the view whose
    4 x 4 scene-to-clip matrix is `clip_from_scene`, from `eye` (scene frame), each at
    the level of detail its distance calls for.

    Tiles are tested by their boxes (egosim.sensors.camera.boxes_in_view).
    """
    if len(tiles.first) == 0:
        return []
    visible = boxes_in_view(tiles.lower, tiles.upper, clip_from_scene)
    nearest = np.clip(eye, tiles.lower, tiles.upper)
    level = (np.linalg.norm(nearest - eye, axis=1) > coarse_beyond_m(focal_px)).astype(np.int64)
    rows = np.flatnonzero(visible)
    firsts = tiles.first[rows, level[rows]]
    counts = tiles.count[rows, level[rows]]
    runs: list[tuple[int, int]] = []
    for first, count in sorted(zip(firsts.tolist(), counts.tolist(), strict=True)):
        if count == 0:
            continue
        if runs and runs[-1][0] + runs[-1][1] == first:
            runs[-1] = (runs[-1][0], runs[-1][1] + count)
        else:
            runs.append((first, count))
    return runs
