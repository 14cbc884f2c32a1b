"""What every placed object reports: ObjectStatus semantics in SI units."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from enum import IntEnum
from itertools import chain

import numpy as np
import numpy.typing as npt

from egosim.world.arrays import FloatArray, IntArray

Vector3 = tuple[float, float, float]


class ObjectType(IntEnum):
    """ObjectStatus.type codes."""

    EGO = -1
    PEDESTRIAN = 0
    NPC_VEHICLE = 1
    OBSTACLE = 2


@dataclass(frozen=True)
class ObjectState:
    """One object. position is the footprint centre on the ground (ENU, m); heading rad
    counter-clockwise from east; velocity (m/s) and acceleration (m/s²) in the map frame;
    size is (length along the heading, width, height), m."""

    unique_id: int
    object_type: ObjectType
    name: str
    position: Vector3
    heading: float
    velocity: Vector3
    acceleration: Vector3
    size: Vector3


@dataclass(frozen=True, eq=False)
class ObjectTable:
    """Many objects as parallel arrays (same meaning as ObjectState's fields)."""

    unique_ids: IntArray
    object_types: IntArray
    names: tuple[str, ...]
    positions: FloatArray
    headings: FloatArray
    velocities: FloatArray
    accelerations: FloatArray
    sizes: FloatArray

    def __len__(self) -> int:
        return len(self.unique_ids)

    def record(self, i: int) -> ObjectState:
        return self.records([i])[0]

    def records(self, rows: Sequence[int] | IntArray) -> list[ObjectState]:
        """ObjectState of each row, in the order given."""
        rows = np.asarray(rows, dtype=np.int64)
        # Whole columns to Python floats at once: per-element conversion costs more than
        # the rest of an object list.
        columns = zip(
            self.unique_ids[rows].tolist(),
            self.object_types[rows].tolist(),
            rows.tolist(),
            self.positions[rows].tolist(),
            self.headings[rows].tolist(),
            self.velocities[rows].tolist(),
            self.accelerations[rows].tolist(),
            self.sizes[rows].tolist(),
            strict=True,
        )
        return [
            ObjectState(
                unique_id=uid,
                object_type=ObjectType(kind),
                name=self.names[row],
                position=tuple(position),
                heading=heading,
                velocity=tuple(velocity),
                acceleration=tuple(accel),
                size=tuple(size),
            )
            for uid, kind, row, position, heading, velocity, accel, size in columns
        ]

    def select(self, mask: npt.ArrayLike) -> ObjectTable:
        """The rows where `mask` is true, in order."""
        keep = np.asarray(mask, dtype=bool)
        return ObjectTable(
            self.unique_ids[keep],
            self.object_types[keep],
            tuple(name for name, kept in zip(self.names, keep, strict=True) if kept),
            self.positions[keep],
            self.headings[keep],
            self.velocities[keep],
            self.accelerations[keep],
            self.sizes[keep],
        )

    @classmethod
    def empty(cls) -> ObjectTable:
        return cls(
            np.empty(0, np.int64),
            np.empty(0, np.int64),
            (),
            np.empty((0, 3)),
            np.empty(0),
            np.empty((0, 3)),
            np.empty((0, 3)),
            np.empty((0, 3)),
        )

    @classmethod
    def concatenate(cls, tables: Sequence[ObjectTable]) -> ObjectTable:
        """The rows of `tables` one after the other (tables are never changed in place, so
        a lone non-empty table is handed out as it is: most parts of a step are empty)."""
        filled = [t for t in tables if len(t.unique_ids)]
        if len(filled) == 1:
            return filled[0]
        if not filled:
            return cls.empty()
        return cls(
            np.concatenate([t.unique_ids for t in filled]),
            np.concatenate([t.object_types for t in filled]),
            tuple(chain.from_iterable(t.names for t in filled)),
            np.concatenate([t.positions for t in filled]),
            np.concatenate([t.headings for t in filled]),
            np.concatenate([t.velocities for t in filled]),
            np.concatenate([t.accelerations for t in filled]),
            np.concatenate([t.sizes for t in filled]),
        )
