"""Scripted objects: vehicles, pedestrians and objects a scenario's storyboard places at
every step (OpenSCENARIO's entities other than the ego).

They are road users like any other to everyone else: listed, seen by sensors, in
collisions (immovable: their motion is dictated), and the simulated NPCs treat the
vehicles and pedestrians on a lane as its occupants (world/populations/scripted.py).
The storyboard hands over the whole table each step.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from egosim.world.traffic.leaders import LaneOccupants
from egosim.world.traffic.objects import ObjectTable, ObjectType


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
_NOBODY = LaneOccupants.empty()


@dataclass(frozen=True, eq=False)
class _Placed:
    """The objects of one kind as placed now."""

    table: ObjectTable
    on_lanes: LaneOccupants
    """Those the storyboard moves along a lane, where it says."""
    unplaced: ObjectTable
    """The others."""


_NONE_PLACED = _Placed(_EMPTY, _NOBODY, _EMPTY)


class ScriptedObjects:
    """The scripted objects of a world, split by kind for the world's tables (and its
    populations: world/populations/scripted.py)."""

    def __init__(self) -> None:
        self._kinds: dict[ObjectType, _Placed] = {}

    def __len__(self) -> int:
        return sum(len(placed.table) for placed in self._kinds.values())

    def clear(self) -> None:
        self._kinds = {}

    def place(self, objects: Sequence[ScriptedObject]) -> None:
        """Show exactly these objects from now on."""
        kinds = {}
        for kind in (ObjectType.NPC_VEHICLE, ObjectType.PEDESTRIAN, ObjectType.OBSTACLE):
            rows = [o for o in objects if o.object_type == kind]
            if rows:
                kinds[kind] = _placed(rows)
        self._kinds = kinds

    def table(self, kind: ObjectType) -> ObjectTable:
        return self._kinds.get(kind, _NONE_PLACED).table

    def on_lanes(self, kind: ObjectType) -> LaneOccupants:
        """Those of `kind` the storyboard moves along a lane: where it says, as fast as
        they go."""
        return self._kinds.get(kind, _NONE_PLACED).on_lanes

    def unplaced(self, kind: ObjectType) -> ObjectTable:
        """Those of `kind` not moved along a lane (their lane is wherever they stand)."""
        return self._kinds.get(kind, _NONE_PLACED).unplaced

    def unique_ids(self) -> set[int]:
        return {int(i) for placed in self._kinds.values() for i in placed.table.unique_ids}


def _placed(rows: Sequence[ScriptedObject]) -> _Placed:
    known = [o for o in rows if o.lane is not None]
    on_lanes = LaneOccupants(
        np.array([o.lane[0] for o in known if o.lane], dtype=np.int64),
        np.array([o.lane[1] for o in known if o.lane], dtype=np.float64),
        np.array([o.size[0] / 2.0 for o in known], dtype=np.float64),
        np.array([float(np.hypot(*o.velocity)) for o in known], dtype=np.float64),
    )
    unknown = [o for o in rows if o.lane is None]
    return _Placed(_table(rows), on_lanes, _table(unknown) if unknown else _EMPTY)


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
