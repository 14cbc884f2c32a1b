"""Scripted objects: vehicles, pedestrians and objects a scenario's storyboard places at
every step (OpenSCENARIO's entities other than the ego).

They are road users like any other to everyone else: listed, seen by sensors, in
collisions (immovable: their motion is dictated), and the simulated NPCs treat those on
a lane as its occupants. The storyboard hands over the whole table each step.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from egosim.world.map import LaneMap
from egosim.world.traffic.leaders import LaneOccupants
from egosim.world.traffic.objects import ObjectTable, ObjectType
from egosim.world.traffic.road_users import lane_occupants_of


@dataclass(frozen=True)
class ScriptedObject:
    """One object as placed now: footprint centre (ENU, m), heading (rad), velocity and
    acceleration (map frame), size (length, width, height)."""

    unique_id: int
    object_type: ObjectType
    name: str
    position: tuple[float, float, float]
    heading: float
    velocity: tuple[float, float]
    acceleration: tuple[float, float]
    size: tuple[float, float, float]
    lane: tuple[int, float] | None = None
    """(lane index, station) of the lane it drives along, if the storyboard knows it."""


_EMPTY = ObjectTable.empty()


class ScriptedObjects:
    """The scripted objects of a world, split by kind for the world's tables."""

    def __init__(self) -> None:
        self._tables: dict[ObjectType, ObjectTable] = {}
        self._on_lanes = LaneOccupants.empty()
        self._unplaced = _EMPTY

    def __len__(self) -> int:
        return sum(len(t) for t in self._tables.values())

    def clear(self) -> None:
        self._tables = {}
        self._on_lanes = LaneOccupants.empty()
        self._unplaced = _EMPTY

    def place(self, objects: Sequence[ScriptedObject]) -> None:
        """Show exactly these objects from now on."""
        tables = {}
        for kind in (ObjectType.NPC_VEHICLE, ObjectType.PEDESTRIAN, ObjectType.OBSTACLE):
            rows = [o for o in objects if o.object_type == kind]
            if rows:
                tables[kind] = _table(rows)
        self._tables = tables
        movers = [o for o in objects if o.object_type != ObjectType.OBSTACLE]
        known = [o for o in movers if o.lane is not None]
        self._on_lanes = LaneOccupants(
            np.array([o.lane[0] for o in known if o.lane], dtype=np.int64),
            np.array([o.lane[1] for o in known if o.lane], dtype=np.float64),
            np.array([o.size[0] / 2.0 for o in known], dtype=np.float64),
            np.array([float(np.hypot(*o.velocity)) for o in known], dtype=np.float64),
        )
        unknown = [o for o in movers if o.lane is None]
        self._unplaced = _table(unknown) if unknown else _EMPTY

    def table(self, kind: ObjectType) -> ObjectTable:
        return self._tables.get(kind, _EMPTY)

    def unique_ids(self) -> set[int]:
        return {int(i) for t in self._tables.values() for i in t.unique_ids}

    def occupants(self, lane_map: LaneMap) -> LaneOccupants:
        """The scripted vehicles and pedestrians standing on a lane: those the storyboard
        moves along a lane where it says, the others where they project."""
        if len(self._unplaced) == 0:
            return self._on_lanes
        return LaneOccupants.concatenate(
            [self._on_lanes, lane_occupants_of(self._unplaced, lane_map)]
        )


def _table(rows: Sequence[ScriptedObject]) -> ObjectTable:
    n = len(rows)
    zeros = np.zeros((n, 1))
    return ObjectTable(
        unique_ids=np.array([o.unique_id for o in rows], dtype=np.int64),
        object_types=np.array([int(o.object_type) for o in rows], dtype=np.int64),
        names=tuple(o.name for o in rows),
        positions=np.array([o.position for o in rows], dtype=np.float64).reshape(-1, 3),
        headings=np.array([o.heading for o in rows], dtype=np.float64),
        velocities=np.hstack(
            (np.array([o.velocity for o in rows], dtype=np.float64).reshape(-1, 2), zeros)
        ),
        accelerations=np.hstack(
            (np.array([o.acceleration for o in rows], dtype=np.float64).reshape(-1, 2), zeros)
        ),
        sizes=np.array([o.size for o in rows], dtype=np.float64).reshape(-1, 3),
    )
