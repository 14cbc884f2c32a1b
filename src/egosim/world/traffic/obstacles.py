"""Static obstacles: boxes that stand still where the scenario puts them."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

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


class StaticObstacles:
    def __init__(self) -> None:
        self.clear()

    def clear(self) -> None:
        self._spawns: list[ObstacleSpawn] = []
        self._table = ObjectTable.empty()

    def __len__(self) -> int:
        return len(self._spawns)

    def spawn(self, spawns: Sequence[ObstacleSpawn]) -> None:
        self._spawns += spawns
        self._build_table()

    def remove(self, unique_id: int) -> bool:
        """Take out the obstacle `unique_id`; False if there is none."""
        kept = [o for o in self._spawns if o.unique_id != unique_id]
        if len(kept) == len(self._spawns):
            return False
        self._spawns = kept
        self._build_table()
        return True

    def _build_table(self) -> None:
        n = len(self._spawns)
        self._table = ObjectTable(
            unique_ids=np.array([o.unique_id for o in self._spawns], dtype=np.int64),
            object_types=np.full(n, int(ObjectType.OBSTACLE), np.int64),
            names=tuple(o.name for o in self._spawns),
            positions=np.array([o.position for o in self._spawns], dtype=np.float64).reshape(-1, 3),
            headings=np.array([o.heading for o in self._spawns], dtype=np.float64),
            velocities=np.zeros((n, 3)),
            accelerations=np.zeros((n, 3)),
            sizes=np.array([o.size for o in self._spawns], dtype=np.float64).reshape(-1, 3),
        )

    def table(self) -> ObjectTable:
        return self._table
