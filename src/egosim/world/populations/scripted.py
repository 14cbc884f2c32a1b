"""A storyboard's vehicles, pedestrians and objects as populations, one per kind (the
tables of world/traffic/scripted.py).

The tick pipeline's storyboard stage places them before the world steps: they do not
step, are immovable in a contact (their motion is the storyboard's) and are never
halted. The simulated NPCs treat the scripted vehicles and pedestrians in a lane as its
occupants; scripted objects stand aside.
"""

from __future__ import annotations

import numpy as np

from egosim.world.arrays import FloatArray, IntArray
from egosim.world.collision import Footprints
from egosim.world.map import LaneProjections
from egosim.world.populations.base import LanePoints, Shove, Surroundings
from egosim.world.traffic import LaneOccupants, ObjectTable, ObjectType
from egosim.world.traffic.road_users import vehicles_on_lanes
from egosim.world.traffic.scripted import ScriptedObjects


class ScriptedPopulation:
    """The scripted objects of one kind, as the storyboard placed them last; in no lane
    (its subclass ScriptedRoadUsers places vehicles and pedestrians)."""

    def __init__(self, scripted: ScriptedObjects, kind: ObjectType) -> None:
        self.scripted = scripted
        self.kind = kind

    def table(self) -> ObjectTable:
        return self.scripted.table(self.kind)

    def footprints(self) -> Footprints:
        return Footprints.of(self.scripted.table(self.kind))

    def lane_points(self) -> LanePoints:
        return LanePoints.none()

    def lane_occupants(self, placed: LaneProjections) -> LaneOccupants:
        return LaneOccupants.empty()

    def inverse_masses(self) -> FloatArray:
        return np.zeros(len(self.table()))

    def step(self, dt: float, surroundings: Surroundings) -> None:
        """The storyboard moves them (before the world steps)."""

    def wait(self, surroundings: Surroundings) -> None:
        """The storyboard decides what they wait for."""

    def shove(self, shove: Shove) -> None:
        """Immovable: their motion is the storyboard's."""

    def halt(self, rows: IntArray) -> None:
        """They go where the storyboard says, collision or not."""


class ScriptedRoadUsers(ScriptedPopulation):
    """Scripted vehicles or pedestrians: those the storyboard moves along a lane stand
    in it where it says, the others where they project (by the rule of NPC vehicles:
    within half their width of a lane's edge, their headings as hints)."""

    def lane_points(self) -> LanePoints:
        unplaced = self.scripted.unplaced(self.kind)
        if len(unplaced) == 0:
            return LanePoints.none()
        return LanePoints(unplaced.positions[:, :2], unplaced.headings)

    def lane_occupants(self, placed: LaneProjections) -> LaneOccupants:
        on_lanes = self.scripted.on_lanes(self.kind)
        unplaced = self.scripted.unplaced(self.kind)
        if len(unplaced) == 0:
            return on_lanes
        return LaneOccupants.concatenate([on_lanes, vehicles_on_lanes(unplaced, placed)])
