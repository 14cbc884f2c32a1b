"""ObjectStatusList semantics: the objects nearest the ego, split by kind."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from egosim.world.arrays import IntArray
from egosim.world.traffic.objects import ObjectState, ObjectTable, ObjectType


@dataclass(frozen=True)
class ObjectList:
    """num_of_*: every object spawned of that kind; the lists: the kinds' share of the
    N objects nearest the ego (N closest overall), each list closest first."""

    num_npcs: int
    num_pedestrians: int
    num_obstacles: int
    npcs: tuple[ObjectState, ...]
    pedestrians: tuple[ObjectState, ...]
    obstacles: tuple[ObjectState, ...]


@dataclass(frozen=True)
class SceneObjects:
    """Every object (World.objects: the egos, then NPC vehicles, pedestrians and
    obstacles) and how many of its rows are egos and of each other kind."""

    table: ObjectTable
    egos: int
    kinds: tuple[int, int, int]
    """Rows of NPC vehicles, pedestrians and obstacles, after the egos' in that order."""


@dataclass(frozen=True)
class NearestObjects:
    """An ObjectList as rows of an object table: the counts, and the rows of `table` in
    each list, closest first (a row that publishes it reads the columns at once)."""

    num_npcs: int
    num_pedestrians: int
    num_obstacles: int
    table: ObjectTable
    npcs: IntArray
    pedestrians: IntArray
    obstacles: IntArray

    def object_list(self) -> ObjectList:
        """The same lists as ObjectState records."""
        listed = (self.npcs, self.pedestrians, self.obstacles)
        records = self.table.records(np.concatenate(listed))
        split = np.cumsum([len(rows) for rows in listed]).tolist()
        return ObjectList(
            num_npcs=self.num_npcs,
            num_pedestrians=self.num_pedestrians,
            num_obstacles=self.num_obstacles,
            npcs=tuple(records[: split[0]]),
            pedestrians=tuple(records[split[0] : split[1]]),
            obstacles=tuple(records[split[1] :]),
        )


# The type codes as plain ints: a numpy comparison with an IntEnum member costs 5 times
# one with its int.
_EGO, _PEDESTRIAN, _NPC_VEHICLE, _OBSTACLE = (
    int(ObjectType.EGO),
    int(ObjectType.PEDESTRIAN),
    int(ObjectType.NPC_VEHICLE),
    int(ObjectType.OBSTACLE),
)


def closest_objects(
    table: ObjectTable,
    candidates: IntArray,
    origin: tuple[float, float],
    size: int,
    counts: tuple[int, int, int],
) -> NearestObjects:
    """The `size` objects among the rows `candidates` of `table` nearest `origin` (plane
    distance from `origin` to each object's position, ties in table order), split into
    vehicles (NPCs and other egos), pedestrians and obstacles."""
    offset = table.positions[candidates, :2] - np.asarray(origin)
    distance = np.hypot(offset[:, 0], offset[:, 1])
    nearest = candidates[np.argsort(distance, kind="stable")[: max(size, 0)]]
    kinds = table.object_types[nearest]
    return NearestObjects(
        num_npcs=counts[0],
        num_pedestrians=counts[1],
        num_obstacles=counts[2],
        table=table,
        # Other egos are vehicles on the road too; they keep their own type code (-1).
        npcs=nearest[(kinds == _NPC_VEHICLE) | (kinds == _EGO)],
        pedestrians=nearest[kinds == _PEDESTRIAN],
        obstacles=nearest[kinds == _OBSTACLE],
    )
