"""Recorded tables as populations: what a replay shows in place of a kind's simulated
agents (see world/recorded_scene.py).

A recorded agent is where the recording says: it does not step, is immovable in a
contact and is never halted, and the next recorded frame replaces the table. Drivers
still see it: each kind stands in lanes by the rule its simulated agents follow.
"""

from __future__ import annotations

import numpy as np

from egosim.world.arrays import FloatArray, IntArray
from egosim.world.collision import Footprints
from egosim.world.map import LaneProjections
from egosim.world.populations.base import LanePoints, Shove, Surroundings
from egosim.world.traffic import LaneOccupants, ObjectTable
from egosim.world.traffic.road_users import (
    obstacles_on_lanes,
    pedestrians_on_lanes,
    vehicles_on_lanes,
)


class RecordedPopulation:
    """A recorded table of one kind; its subclasses add how the kind stands in lanes
    (lane_occupants)."""

    def __init__(self, table: ObjectTable) -> None:
        self.recorded = table

    def table(self) -> ObjectTable:
        return self.recorded

    def footprints(self) -> Footprints:
        return Footprints.of(self.recorded)

    def lane_points(self) -> LanePoints:
        """Every recorded position, without a heading hint."""
        table = self.recorded
        return LanePoints(table.positions[:, :2], np.full(len(table), np.nan))

    def inverse_masses(self) -> FloatArray:
        return np.zeros(len(self.recorded))

    def step(self, dt: float, surroundings: Surroundings) -> None:
        """The recording moves it, frame by frame."""

    def shove(self, shove: Shove) -> None:
        """Immovable: its motion is the recording's."""

    def halt(self, rows: IntArray) -> None:
        """It goes where the recording says, collision or not."""


class RecordedVehicles(RecordedPopulation):
    """Recorded NPC vehicles, in lanes like NPC ghosts (their headings as hints)."""

    def lane_points(self) -> LanePoints:
        return LanePoints(self.recorded.positions[:, :2], self.recorded.headings)

    def lane_occupants(self, placed: LaneProjections) -> LaneOccupants:
        return vehicles_on_lanes(self.recorded, placed)


class RecordedPedestrians(RecordedPopulation):
    """Recorded pedestrians, any of whom may stand in a lane."""

    def lane_occupants(self, placed: LaneProjections) -> LaneOccupants:
        return pedestrians_on_lanes(placed)


class RecordedObstacles(RecordedPopulation):
    def lane_occupants(self, placed: LaneProjections) -> LaneOccupants:
        return obstacles_on_lanes(self.recorded, placed)
