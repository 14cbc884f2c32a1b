"""Triangle lists for the cameras: the Mesh a renderer draws and the shapes it is made of.

Colours are shaded once on the CPU by a fixed sun (Lambert plus ambient), so the same
state always gives the same triangles. A static scene is kept at two levels of detail
(see egosim.sensors.scene_tiles); each part says at which levels it is drawn.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from enum import Flag

import numpy as np
import numpy.typing as npt

from egosim.sensors.camera_labels import SEMANTIC_PALETTE, SemanticClass, instance_colors
from egosim.world.arrays import FloatArray, IntArray

SUN_DIRECTION = np.array([0.4, 0.3, 1.0]) / np.linalg.norm([0.4, 0.3, 1.0])
AMBIENT = 0.55

# The unit cube's 12 triangles, outward normals, as corner indices of (±1, ±1, ±1).
_CORNERS = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], float)
_FACES = (
    ((0, 1, 3, 2), (-1, 0, 0)),
    ((4, 6, 7, 5), (1, 0, 0)),
    ((0, 4, 5, 1), (0, -1, 0)),
    ((2, 3, 7, 6), (0, 1, 0)),
    ((0, 2, 6, 4), (0, 0, -1)),
    ((1, 5, 7, 3), (0, 0, 1)),
)
_CUBE_TRIANGLES = np.array(
    [
        [a, b, c]
        for quad, _ in _FACES
        for a, b, c in ((quad[0], quad[1], quad[2]), (quad[0], quad[2], quad[3]))
    ]
).reshape(-1)
_CUBE_NORMALS = np.repeat(np.array([n for _, n in _FACES], float), 6, axis=0)


class Detail(Flag):
    """The levels of detail a part of a static scene is drawn at."""

    FINE = 1
    COARSE = 2
    BOTH = FINE | COARSE


@dataclass(frozen=True, eq=False)
class Mesh:
    """A triangle list: 3 consecutive vertices per triangle.

    positions (N, 3) float32 in the scene frame (the map frame moved by the scene's
    origin); colors (N, 3) uint8 shaded RGB; semantic (N, 3) uint8 class colours;
    instance (N, 3) uint8 instance colours.
    """

    positions: npt.NDArray[np.float32]
    colors: npt.NDArray[np.uint8]
    semantic: npt.NDArray[np.uint8]
    instance: npt.NDArray[np.uint8]

    def __len__(self) -> int:
        return len(self.positions)

    def reordered(self, vertex_order: IntArray) -> Mesh:
        """The vertices in `vertex_order` (an index may repeat)."""
        return Mesh(
            self.positions[vertex_order],
            self.colors[vertex_order],
            self.semantic[vertex_order],
            self.instance[vertex_order],
        )

    @classmethod
    def empty(cls) -> Mesh:
        return cls(
            np.empty((0, 3), np.float32),
            np.empty((0, 3), np.uint8),
            np.empty((0, 3), np.uint8),
            np.empty((0, 3), np.uint8),
        )


@dataclass(frozen=True)
class _Part:
    triangles: FloatArray
    colors: FloatArray
    label: SemanticClass
    instances: IntArray
    detail: Detail


class MeshBuilder:
    """Collects triangles with their colour, class, instance and level of detail, in
    scene coordinates (the map frame less `origin`)."""

    def __init__(self, origin: FloatArray) -> None:
        self._origin = origin
        self._parts: list[_Part] = []

    def add(
        self,
        triangles: FloatArray,
        colors: npt.ArrayLike,
        label: SemanticClass,
        instances: npt.ArrayLike = 0,
        detail: Detail = Detail.BOTH,
    ) -> None:
        """`triangles` (N, 3) map points; `colors` one RGB or (N, 3); instances one or (N,)."""
        if len(triangles) == 0:
            return
        count = len(triangles)
        shaded = np.broadcast_to(np.asarray(colors, dtype=np.float64), (count, 3))
        ids = np.broadcast_to(np.asarray(instances, dtype=np.int64), (count,))
        self._parts.append(_Part(triangles - self._origin, shaded, label, ids, detail))

    def mesh(self) -> Mesh:
        """Every part's triangles, in the order they were added."""
        parts = self._parts
        if not parts:
            return Mesh.empty()
        positions = np.concatenate([p.triangles for p in parts]).astype(np.float32)
        colors = np.concatenate([p.colors for p in parts])
        labels = np.concatenate([np.full(len(p.triangles), int(p.label)) for p in parts])
        ids = np.concatenate([p.instances for p in parts])
        return Mesh(
            positions,
            np.clip(np.rint(colors), 0, 255).astype(np.uint8),
            SEMANTIC_PALETTE[labels],
            instance_colors(ids),
        )

    def triangle_details(self) -> IntArray:
        """The Detail value of each triangle of mesh()."""
        if not self._parts:
            return np.empty(0, np.int64)
        return np.concatenate([np.full(len(p.triangles) // 3, p.detail.value) for p in self._parts])


def sunlight(normals: FloatArray) -> FloatArray:
    """(N,) brightness of surfaces with unit `normals` (N, 3): ambient plus Lambert."""
    light: FloatArray = AMBIENT + (1.0 - AMBIENT) * np.maximum(normals @ SUN_DIRECTION, 0.0)
    return light


def flat_color(color: Sequence[int]) -> FloatArray:
    """A colour on an upward-facing surface."""
    return np.asarray(color, dtype=np.float64) * float(sunlight(np.array([[0.0, 0.0, 1.0]]))[0])


def ribbon(left: FloatArray, right: FloatArray) -> FloatArray:
    """Triangles (6 (N - 1), 3) of the strip between two (N, 3) polylines."""
    a, b, c, d = left[:-1], right[:-1], right[1:], left[1:]
    return np.stack([a, b, c, a, c, d], axis=1).reshape(-1, 3)


def _box_triangles(
    centres: FloatArray, sizes: FloatArray, yaws: FloatArray
) -> tuple[FloatArray, FloatArray]:
    """Triangles (36 N, 3) and their normals of upright boxes (centre, size L W H, yaw)."""
    cos, sin = np.cos(yaws), np.sin(yaws)
    corners = _CORNERS[_CUBE_TRIANGLES][None, :, :] * (sizes[:, None, :] / 2.0)
    x = cos[:, None] * corners[..., 0] - sin[:, None] * corners[..., 1]
    y = sin[:, None] * corners[..., 0] + cos[:, None] * corners[..., 1]
    points = np.stack([x, y, corners[..., 2]], axis=-1) + centres[:, None, :]
    nx = cos[:, None] * _CUBE_NORMALS[None, :, 0] - sin[:, None] * _CUBE_NORMALS[None, :, 1]
    ny = sin[:, None] * _CUBE_NORMALS[None, :, 0] + cos[:, None] * _CUBE_NORMALS[None, :, 1]
    nz = np.broadcast_to(_CUBE_NORMALS[None, :, 2], nx.shape)
    normals = np.stack([nx, ny, nz], axis=-1)
    return points.reshape(-1, 3), normals.reshape(-1, 3)


def add_boxes(
    builder: MeshBuilder,
    centres: FloatArray,
    sizes: FloatArray,
    yaws: FloatArray,
    colors: npt.ArrayLike,
    label: SemanticClass,
    instances: npt.ArrayLike = 0,
) -> None:
    """Boxes shaded per face; colors (N, 3) or one; instances (N,) or one."""
    if len(centres) == 0:
        return
    points, normals = _box_triangles(centres, sizes, yaws)
    base = np.repeat(np.broadcast_to(np.asarray(colors, float), (len(centres), 3)), 36, axis=0)
    light = sunlight(normals)
    ids = np.repeat(np.broadcast_to(np.asarray(instances, np.int64), (len(centres),)), 36)
    builder.add(points, base * light[:, None], label, ids)
