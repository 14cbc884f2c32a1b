"""The simulated agents of world/traffic as populations: NPC vehicles, NPC ghosts,
pedestrians and obstacles."""

from __future__ import annotations

import numpy as np

from egosim.world.arrays import BoolArray, FloatArray, IntArray
from egosim.world.collision import Footprints
from egosim.world.map import LaneMap, LaneProjections
from egosim.world.populations.base import LanePoints, Shove, Surroundings
from egosim.world.signals import OFF, RED
from egosim.world.traffic import (
    CrosswalkLights,
    LaneOccupants,
    LightsView,
    NpcFleet,
    ObjectTable,
    PedestrianCrowd,
    StaticObstacles,
)
from egosim.world.traffic.ghosts import NpcGhosts
from egosim.world.traffic.road_users import (
    obstacles_on_lanes,
    pedestrians_on_lanes,
    vehicles_on_lanes,
)

PEDESTRIAN_MASS_KG = 75.0


class SimulatedNpcs:
    """The NPC vehicles that drive themselves (the IDM lane followers of NpcFleet); a
    dormant one sets off when an ego has come within its active distance."""

    def __init__(self, fleet: NpcFleet) -> None:
        self.fleet = fleet

    def table(self) -> ObjectTable:
        return self.fleet.table()

    def footprints(self) -> Footprints:
        pose, dims = self.fleet.pose, self.fleet.dims
        return Footprints(pose[:, :2], pose[:, 3], dims[:, 0], dims[:, 1])

    def lane_points(self) -> LanePoints:
        return LanePoints.none()

    def lane_occupants(self, placed: LaneProjections) -> LaneOccupants:
        return self.fleet.occupants()

    def inverse_masses(self) -> FloatArray:
        """A parked NPC (still waiting to set off) is immovable."""
        inverse: FloatArray = np.where(self.fleet.parked(), 0.0, 1.0 / self.fleet.mass)
        return inverse

    def step(self, dt: float, surroundings: Surroundings) -> None:
        self.wait(surroundings)
        # An empty fleet has no driver to place anyone on lanes for.
        if len(self.fleet):
            self.fleet.step(dt, surroundings.lights, surroundings.occupants_besides(self))

    def wait(self, surroundings: Surroundings) -> None:
        if self.fleet.dormant.any():
            self.fleet.wake(surroundings.ego_positions())

    def shove(self, shove: Shove) -> None:
        self.fleet.shove(shove.rows, shove.displacements, shove.velocities)

    def halt(self, rows: IntArray) -> None:
        self.fleet.stop(rows)


class PlacedGhosts:
    """The NPC ghosts: NPC vehicles that stand where NpcGhostCmd last put them, immovable
    in a contact (their motion is the client's)."""

    def __init__(self, ghosts: NpcGhosts) -> None:
        self.ghosts = ghosts

    def table(self) -> ObjectTable:
        return self.ghosts.table()

    def footprints(self) -> Footprints:
        return Footprints.of(self.ghosts.table())

    def lane_points(self) -> LanePoints:
        table = self.ghosts.table()
        if len(table) == 0:
            return LanePoints.none()
        return LanePoints(table.positions[:, :2], table.headings)

    def lane_occupants(self, placed: LaneProjections) -> LaneOccupants:
        return vehicles_on_lanes(self.ghosts.table(), placed)

    def inverse_masses(self) -> FloatArray:
        return np.zeros(len(self.ghosts))

    def step(self, dt: float, surroundings: Surroundings) -> None:
        """Ghosts move only when placed."""

    def wait(self, surroundings: Surroundings) -> None:
        """A ghost waits for nothing."""

    def shove(self, shove: Shove) -> None:
        """Immovable: no contact moves a ghost."""

    def halt(self, rows: IntArray) -> None:
        """A ghost goes where it is placed, collision or not."""


class SimulatedPedestrians:
    """The pedestrians walking their paths, waiting at crosswalks for the walk signal; a
    dormant one sets off when an ego has come within its active distance."""

    def __init__(self, crowd: PedestrianCrowd, crosswalk_lights: CrosswalkLights) -> None:
        self.crowd = crowd
        self.crosswalk_lights = crosswalk_lights
        self._walk_signals: tuple[LightsView, BoolArray] | None = None

    def table(self) -> ObjectTable:
        return self.crowd.table()

    def footprints(self) -> Footprints:
        crowd = self.crowd
        return Footprints(crowd.position, crowd.heading, crowd.dims[:, 0], crowd.dims[:, 1])

    def lane_points(self) -> LanePoints:
        """Those who may stand in a lane: sidewalk walkers never leave the kerb."""
        walkers = self.crowd.position[self.crowd.on_road]
        return LanePoints(walkers, np.full(len(walkers), np.nan))

    def lane_occupants(self, placed: LaneProjections) -> LaneOccupants:
        return pedestrians_on_lanes(placed)

    def inverse_masses(self) -> FloatArray:
        return np.full(len(self.crowd), 1.0 / PEDESTRIAN_MASS_KG)

    def step(self, dt: float, surroundings: Surroundings) -> None:
        self.wait(surroundings)
        self.crowd.step(dt, self._walk_signals_of(surroundings.lights))

    def _walk_signals_of(self, lights: LightsView) -> BoolArray:
        """The crosswalks' walk signals under `lights`, kept while the view is the same
        (the world hands out one view until an aspect changes)."""
        known = self._walk_signals
        if known is None or known[0] is not lights:
            stops_traffic = (lights.aspects == RED) | (lights.aspects == OFF) | lights.flashing
            known = self._walk_signals = (lights, self.crosswalk_lights.walk_signals(stops_traffic))
        return known[1]

    def wait(self, surroundings: Surroundings) -> None:
        if self.crowd.dormant.any():
            self.crowd.wake(surroundings.ego_positions())

    def shove(self, shove: Shove) -> None:
        self.crowd.shove(shove.rows, shove.displacements)

    def halt(self, rows: IntArray) -> None:
        self.crowd.stop(rows)


class SimulatedObstacles:
    """The obstacles: they stand, and slide to a stop when a contact pushed them."""

    def __init__(self, obstacles: StaticObstacles, lane_map: LaneMap) -> None:
        self.obstacles = obstacles
        self.map = lane_map
        self._occupants: tuple[ObjectTable, LaneOccupants] | None = None

    def table(self) -> ObjectTable:
        return self.obstacles.table()

    def footprints(self) -> Footprints:
        return Footprints.of(self.obstacles.table())

    def lane_points(self) -> LanePoints:
        return LanePoints.none()

    def lane_occupants(self, placed: LaneProjections) -> LaneOccupants:
        """Placed on lanes again only when the obstacles changed: StaticObstacles builds
        a new table whenever one is added, removed or moved."""
        table = self.obstacles.table()
        known = self._occupants
        if known is None or known[0] is not table:
            occupants = (
                obstacles_on_lanes(table, self.map.project_many(table.positions[:, :2]))
                if len(table)
                else LaneOccupants.empty()
            )
            known = self._occupants = (table, occupants)
        return known[1]

    def inverse_masses(self) -> FloatArray:
        return self.obstacles.inverse_masses()

    def step(self, dt: float, surroundings: Surroundings) -> None:
        self.obstacles.step(dt)

    def wait(self, surroundings: Surroundings) -> None:
        """An obstacle waits for nothing."""

    def shove(self, shove: Shove) -> None:
        self.obstacles.shove(shove.rows, shove.displacements, shove.velocities)

    def halt(self, rows: IntArray) -> None:
        """A struck obstacle is moved by the contact response alone."""
