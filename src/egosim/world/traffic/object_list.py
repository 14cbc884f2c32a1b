"""ObjectStatusList semantics: the objects nearest the ego, split by kind."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

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


def closest_objects(
    table: ObjectTable, origin: tuple[float, float], size: int, counts: tuple[int, int, int]
) -> ObjectList:
    """The `size` objects of `table` nearest `origin` (plane distance from `origin` to
    each object's position, ties in table order), split into vehicles (NPCs and other
    egos), pedestrians and obstacles."""
    offset = table.positions[:, :2] - np.asarray(origin)
    distance = np.hypot(offset[:, 0], offset[:, 1])
    nearest = np.argsort(distance, kind="stable")[: max(size, 0)]
    records = table.records(nearest)

    def of(*kinds: ObjectType) -> tuple[ObjectState, ...]:
        return tuple(r for r in records if r.object_type in kinds)

    return ObjectList(
        num_npcs=counts[0],
        num_pedestrians=counts[1],
        num_obstacles=counts[2],
        # Other egos are vehicles on the road too; they keep their own type code (-1).
        npcs=of(ObjectType.NPC_VEHICLE, ObjectType.EGO),
        pedestrians=of(ObjectType.PEDESTRIAN),
        obstacles=of(ObjectType.OBSTACLE),
    )
