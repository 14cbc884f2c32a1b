"""The interface every kind of agent has towards the world: Population.

A population is a group of agents of one kind that the world steps and shows as one
block of rows of its object table: the egos, the simulated NPC vehicles, the NPC
ghosts, the pedestrians, the obstacles, those a storyboard places, or a recorded table
that a replay shows in place of a kind's own populations. The world keeps no per-kind
logic of its own: it orders the populations, steps them, and lets
world/contact_handling.py answer their contacts through the same interface.

A row index handed to a population (`Shove.rows`, `halt`) counts within the
population's own table.
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Protocol

import numpy as np

from egosim.world.arrays import FloatArray, IntArray
from egosim.world.collision import Footprints
from egosim.world.map import LaneMap, LaneProjections, ProjectionMemory
from egosim.world.traffic import LaneOccupants, LightsView, ObjectTable
from egosim.world.vehicle import VehicleStatus


@dataclass(frozen=True, eq=False)
class LanePoints:
    """Points to place on lanes: (N, 2) positions, m, and (N,) heading hints, rad (NaN:
    no hint for that point)."""

    xy: FloatArray
    headings: FloatArray

    @classmethod
    def none(cls) -> LanePoints:
        return _NO_POINTS


_NO_POINTS = LanePoints(np.empty((0, 2)), np.empty(0))
_NOWHERE = LaneProjections(
    lane_ids=(),
    lane_index=np.empty(0, np.int64),
    s=np.empty(0),
    lateral=np.empty(0),
    heading=np.empty(0),
    distance_left=np.empty(0),
    distance_right=np.empty(0),
    width=np.empty(0),
)
"""The projections of no points, for the many populations that place nobody."""


@dataclass(frozen=True, eq=False)
class Shove:
    """What a contact response does to some rows of a population: move them by
    `displacements` (K, 2) m, after which they move at `velocities` (K, 2) m/s, a change
    of `velocity_changes` (K, 2) m/s; all in the map frame."""

    rows: IntArray
    displacements: FloatArray
    velocities: FloatArray
    velocity_changes: FloatArray


class Population(Protocol):
    """One kind of agent's share of the world."""

    def table(self) -> ObjectTable:
        """Its rows of the object table, in a fixed order."""
        ...

    def footprints(self) -> Footprints:
        """The footprints of its rows of the object table (their positions, headings,
        lengths and widths), without the table's other columns: every step's collision
        test asks for them."""
        ...

    def lane_points(self) -> LanePoints:
        """The points it needs placed on lanes to say who of it stands where (none if
        it knows its lanes)."""
        ...

    def lane_occupants(self, placed: LaneProjections) -> LaneOccupants:
        """Who of it stands in a lane now, for the drivers behind; `placed` holds the
        projections of its lane_points."""
        ...

    def inverse_masses(self) -> FloatArray:
        """Per row, 1/kg in a contact; 0: immovable (its motion is dictated or it is
        fixed to the ground)."""
        ...

    def step(self, dt: float, surroundings: Surroundings) -> None:
        """Move on by dt s."""
        ...

    def shove(self, shove: Shove) -> None:
        """Take a contact response (only rows of non-zero inverse mass get one)."""
        ...

    def halt(self, rows: IntArray) -> None:
        """A collision with an ego or between NPC vehicles began for these rows (a crashed
        driver brakes to a stop, a struck pedestrian stays)."""
        ...


class Replaceable(Population, Protocol):
    """A population of the world's own agents, which a replay's recorded table of its
    kind can stand in for (World.show_recorded)."""

    def wait(self, surroundings: Surroundings) -> None:
        """A step while a recording stands in for it: it stays as it is, but notices what
        it waits for (a dormant NPC or pedestrian wakes when an ego has come near)."""
        ...


class EgoPopulation(Population, Protocol):
    """The egos, with what the world reports of each (by index, the main ego first)."""

    def status(self, index: int) -> VehicleStatus:
        """The ego's state as the protocol reports it."""
        ...

    def lanes(self) -> LaneProjections:
        """Where each ego's reference point lies on its lane (its yaw as the hint)."""
        ...

    def positions(self) -> FloatArray:
        """(N, 2) each ego's reference point (its reported position), m."""
        ...


class Surroundings:
    """What the populations of a step move among: the lights, where the egos are, who
    stands in which lane.

    The egos' positions and the lane occupants are worked out when a population first
    asks, the occupants with one lane projection for every population's points, and are
    then kept for the rest of the step: the populations step in order (the egos first),
    so those asking see the ones before them where they now are, and the others where
    the step found them.
    """

    def __init__(
        self,
        lane_map: LaneMap,
        lights: LightsView,
        populations: Sequence[Population],
        egos: EgoPopulation | None = None,
        memory: ProjectionMemory | None = None,
    ) -> None:
        """`egos`: the egos among `populations`, whom dormant agents wait for (none: a
        world of no egos, where nobody wakes). `memory`: the lane projection's of the
        last step, kept by the caller from step to step (see place_on_lanes)."""
        self.lights = lights
        self._map = lane_map
        self._egos = egos
        self._populations = populations
        self._memory = memory
        self._ego_positions: FloatArray | None = None
        self._occupants: list[LaneOccupants] | None = None

    def ego_positions(self) -> FloatArray:
        """(N, 2) each ego's reference point, m (see EgoPopulation.positions)."""
        if self._ego_positions is None:
            egos = self._egos
            self._ego_positions = np.empty((0, 2)) if egos is None else egos.positions()
        return self._ego_positions

    def occupants_besides(self, population: Population) -> LaneOccupants:
        """Every other population's lane occupants, in the populations' order."""
        if self._occupants is None:
            self._occupants = place_on_lanes(self._map, self._populations, self._memory)
        return LaneOccupants.concatenate(
            [
                occupants
                for other, occupants in zip(self._populations, self._occupants, strict=True)
                if other is not population
            ]
        )


def place_on_lanes(
    lane_map: LaneMap, populations: Sequence[Population], memory: ProjectionMemory | None = None
) -> list[LaneOccupants]:
    """Each population's lane occupants, from one projection of all their lane points;
    `memory` is the projection's of the last call (the same populations, a step ago), if
    the caller keeps one: those who have not moved are not searched for again."""
    points = [population.lane_points() for population in populations]
    filled = [p for p in points if len(p.headings)]
    if not filled:
        return [population.lane_occupants(_NOWHERE) for population in populations]
    placed = lane_map.project_many(
        np.concatenate([p.xy for p in filled]),
        np.concatenate([p.headings for p in filled]),
        memory,
    )
    bounds = list(itertools.accumulate([len(p.headings) for p in points], initial=0))
    return [
        population.lane_occupants(placed.part(start, stop) if stop > start else _NOWHERE)
        for population, start, stop in zip(populations, bounds[:-1], bounds[1:], strict=True)
    ]
