"""Obstacles: boxes that stand where the scenario puts them until a vehicle pushes the
light ones aside (world/contact.py)."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace

import numpy as np

from egosim.world.arrays import FloatArray, IntArray
from egosim.world.traffic.catalogue import OBSTACLE_MODELS
from egosim.world.traffic.objects import ObjectTable, ObjectType


@dataclass(frozen=True)
class ObstacleSpawn:
    """A box named `name`: footprint centre (x, y, z) m, heading rad, size (length, width,
    height) m."""

    unique_id: int
    name: str
    position: tuple[float, float, float]
    heading: float
    size: tuple[float, float, float]


SLIDE_DECEL_MPS2 = 0.5 * 9.81
"""A pushed obstacle slides on the road with friction coefficient 0.5."""


class StaticObstacles:
    def __init__(self) -> None:
        self.clear()

    def clear(self) -> None:
        self._spawns: list[ObstacleSpawn] = []
        self._velocities: FloatArray = np.zeros((0, 2))
        self._table = ObjectTable.empty()

    def __len__(self) -> int:
        return len(self._spawns)

    def spawn(self, spawns: Sequence[ObstacleSpawn]) -> None:
        self._spawns += spawns
        self._velocities = np.vstack((self._velocities, np.zeros((len(spawns), 2))))
        self._build_table()

    def remove(self, unique_id: int) -> bool:
        """Take out the obstacle `unique_id`; False if there is none."""
        keep = [o.unique_id != unique_id for o in self._spawns]
        if all(keep):
            return False
        self._spawns = [o for o, k in zip(self._spawns, keep, strict=True) if k]
        self._velocities = self._velocities[np.array(keep, dtype=bool)]
        self._build_table()
        return True

    def inverse_masses(self) -> FloatArray:
        """Per obstacle, 1/kg: 0 for an immovable one (a barrier, an unknown model)."""
        masses = [getattr(OBSTACLE_MODELS.get(o.name), "mass_kg", None) for o in self._spawns]
        return np.array([0.0 if m is None else 1.0 / m for m in masses])

    def shove(self, indices: IntArray, displacement: FloatArray, velocity: FloatArray) -> None:
        """A contact's response: push obstacles `indices` by `displacement` (K, 2) m and
        set them sliding at `velocity` (K, 2) m/s, map frame."""
        self._velocities[indices] = velocity
        self._move(indices, displacement)

    def step(self, dt: float) -> bool:
        """Sliding obstacles move on, slowed by ground friction to a stop; True if any
        moved."""
        if not self._velocities.any():
            return False
        speed = np.hypot(self._velocities[:, 0], self._velocities[:, 1])
        sliding = np.flatnonzero(speed > 0.0)
        if sliding.size == 0:
            return False
        slower = np.maximum(speed[sliding] - SLIDE_DECEL_MPS2 * dt, 0.0) / speed[sliding]
        before = self._velocities[sliding].copy()
        self._velocities[sliding] *= slower[:, None]
        self._move(sliding, 0.5 * (before + self._velocities[sliding]) * dt)
        return True

    def _move(self, indices: IntArray, displacement: FloatArray) -> None:
        for k, (dx, dy) in zip(indices.tolist(), displacement.tolist(), strict=True):
            x, y, z = self._spawns[k].position
            self._spawns[k] = replace(self._spawns[k], position=(x + dx, y + dy, z))
        self._build_table()

    def _build_table(self) -> None:
        n = len(self._spawns)
        self._table = ObjectTable(
            unique_ids=np.array([o.unique_id for o in self._spawns], dtype=np.int64),
            object_types=np.full(n, int(ObjectType.OBSTACLE), np.int64),
            names=tuple(o.name for o in self._spawns),
            positions=np.array([o.position for o in self._spawns], dtype=np.float64).reshape(-1, 3),
            headings=np.array([o.heading for o in self._spawns], dtype=np.float64),
            velocities=np.column_stack((self._velocities, np.zeros(n))),
            accelerations=np.zeros((n, 3)),
            sizes=np.array([o.size for o in self._spawns], dtype=np.float64).reshape(-1, 3),
        )

    def table(self) -> ObjectTable:
        return self._table
