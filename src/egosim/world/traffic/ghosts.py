"""NPC ghosts: NPC vehicles placed from outside (NpcGhostCmd) instead of simulated.

A ghost stays where its last placement put it until the next one. It is an NPC vehicle
to everybody else: it is listed and collides like one, and the simulated NPCs treat it
as an occupant of the lane it stands on.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from enum import IntEnum

import numpy as np

from egosim.world.traffic.objects import ObjectTable, ObjectType
from egosim.world.vehicle import VehicleModel

_NO_GHOSTS = ObjectTable.empty()
"""The table of no ghosts (tables are never changed in place)."""


class TurnSignal(IntEnum):
    """NpcGhostInfo.turn_signal."""

    OFF = 0
    LEFT = 1
    RIGHT = 2
    HAZARD = 3


@dataclass(frozen=True)
class GhostPlacement:
    """Where one ghost is now: footprint centre (ENU, m), heading (rad, 0 = east, CCW),
    speed along the heading (m/s), front wheel angle (rad) and its lamps."""

    unique_id: int
    model: VehicleModel
    """Its catalogue model (kept from the first placement of that id)."""
    position: tuple[float, float, float]
    heading: float
    speed: float = 0.0
    front_steer: float = 0.0
    turn_signal: TurnSignal = TurnSignal.OFF
    brake_light: bool = False


@dataclass
class GhostState:
    placement: GhostPlacement
    acceleration: float
    """Along the heading, m/s², from the speeds of the last two placements."""
    placed_at: float
    """Simulation time of the last placement, s."""


class NpcGhosts:
    """Every NPC ghost of a world, in the order they first appeared."""

    def __init__(self) -> None:
        self._ghosts: dict[int, GhostState] = {}
        self._table: ObjectTable | None = None
        """The ghosts' table, built once per placement: every step asks for it."""

    def __len__(self) -> int:
        return len(self._ghosts)

    def __contains__(self, unique_id: int) -> bool:
        return unique_id in self._ghosts

    def clear(self) -> None:
        self._ghosts.clear()
        self._table = None

    @property
    def unique_ids(self) -> list[int]:
        return list(self._ghosts)

    def get(self, unique_id: int) -> GhostPlacement:
        return self._ghosts[unique_id].placement

    def place(self, placements: Sequence[GhostPlacement], sim_time: float) -> None:
        """Put each ghost where its placement says; a new id becomes a new ghost."""
        self._table = None
        for placement in placements:
            previous = self._ghosts.get(placement.unique_id)
            if previous is None:
                self._ghosts[placement.unique_id] = GhostState(placement, 0.0, sim_time)
                continue
            elapsed = sim_time - previous.placed_at
            if elapsed > 0.0:
                previous.acceleration = (placement.speed - previous.placement.speed) / elapsed
                previous.placed_at = sim_time
            # The body is the one the ghost first appeared as; later names do not rebuild it.
            previous.placement = GhostPlacement(
                placement.unique_id,
                previous.placement.model,
                placement.position,
                placement.heading,
                placement.speed,
                placement.front_steer,
                placement.turn_signal,
                placement.brake_light,
            )

    def table(self) -> ObjectTable:
        if self._table is None:
            self._table = self._build_table()
        return self._table

    def _build_table(self) -> ObjectTable:
        states = list(self._ghosts.values())
        if not states:
            return _NO_GHOSTS
        n = len(states)
        heading = np.array([g.placement.heading for g in states])
        direction = np.column_stack((np.cos(heading), np.sin(heading), np.zeros(n)))
        speed = np.array([g.placement.speed for g in states])
        acceleration = np.array([g.acceleration for g in states])
        models = [g.placement.model for g in states]
        return ObjectTable(
            unique_ids=np.array([g.placement.unique_id for g in states], dtype=np.int64),
            object_types=np.full(n, int(ObjectType.NPC_VEHICLE), np.int64),
            names=tuple(m.name for m in models),
            positions=np.array([g.placement.position for g in states], dtype=np.float64),
            headings=heading,
            velocities=speed[:, None] * direction,
            accelerations=acceleration[:, None] * direction,
            sizes=np.array([(m.length, m.width, m.height) for m in models], dtype=np.float64),
        )
