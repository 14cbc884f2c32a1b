"""Contact handling through the Population interface: each population gets its own rows
halted and shoved, with the closed-form response of a body hitting an immovable one."""

from __future__ import annotations

import numpy as np
import pytest

from egosim.world.arrays import FloatArray, IntArray
from egosim.world.collision import Footprints
from egosim.world.contact import RESTITUTION, ContactModel
from egosim.world.contact_handling import ContactHandler
from egosim.world.map import LaneProjections, build_builtin_map
from egosim.world.populations import LanePoints, Population, Shove, Surroundings
from egosim.world.signals import TrafficSignals
from egosim.world.traffic import LaneOccupants, LightsView, ObjectTable, ObjectType

STRAIGHT = build_builtin_map("straight")
DT = 0.01
LENGTH_M, WIDTH_M = 4.0, 2.0


class Cars:
    """NPC vehicles as boxes along y = 0 at constant velocities (a population of the
    test's own), remembering what contact handling did to them."""

    def __init__(self, first_id: int, x: list[float], vx: list[float], mass_kg: float) -> None:
        self.ids = np.arange(first_id, first_id + len(x), dtype=np.int64)
        self.x, self.vx = np.array(x), np.array(vx)
        self.inverse = 1.0 / mass_kg  # 0 for an infinite mass: immovable
        self.halted: list[list[int]] = []
        self.shoves: list[Shove] = []

    def table(self) -> ObjectTable:
        n = len(self.x)
        return ObjectTable(
            unique_ids=self.ids,
            object_types=np.full(n, int(ObjectType.NPC_VEHICLE), np.int64),
            names=("car",) * n,
            positions=np.column_stack((self.x, np.zeros(n), np.zeros(n))),
            headings=np.zeros(n),
            velocities=np.column_stack((self.vx, np.zeros(n), np.zeros(n))),
            accelerations=np.zeros((n, 3)),
            sizes=np.tile((LENGTH_M, WIDTH_M, 1.5), (n, 1)),
        )

    def footprints(self) -> Footprints:
        return Footprints.of(self.table())

    def lane_points(self) -> LanePoints:
        return LanePoints.none()

    def lane_occupants(self, placed: LaneProjections) -> LaneOccupants:
        return LaneOccupants.empty()

    def inverse_masses(self) -> FloatArray:
        return np.full(len(self.x), self.inverse)

    def step(self, dt: float, surroundings: Surroundings) -> None:
        self.x = self.x + self.vx * dt

    def shove(self, shove: Shove) -> None:
        self.shoves.append(shove)
        self.x[shove.rows] += shove.displacements[:, 0]
        self.vx[shove.rows] = shove.velocities[:, 0]

    def halt(self, rows: IntArray) -> None:
        self.halted.append(rows.tolist())


def run(handler: ContactHandler, populations: list[Population], steps: int) -> list[int]:
    """Step the populations and their contacts; the steps in which a collision began."""
    lights = LightsView.of(TrafficSignals(STRAIGHT))
    began = []
    for k in range(steps):
        surroundings = Surroundings(STRAIGHT, lights, populations)
        for population in populations:
            population.step(DT, surroundings)
        if handler.step(populations, ContactModel(), (k + 1) * DT).vehicle_collisions:
            began.append(k)
    return began


def test_each_population_answers_for_its_own_rows_and_a_car_bounces_off_a_wall() -> None:
    # The third moving car drives at 5 m/s into an immovable one 0.98 m ahead of it.
    moving = Cars(1, [-40.0, -20.0, 0.0], [0.0, 0.0, 5.0], mass_kg=1500.0)
    parked = Cars(10, [LENGTH_M + 0.98], [0.0], mass_kg=np.inf)
    populations: list[Population] = [moving, parked]
    handler = ContactHandler(ObjectTable.concatenate([p.table() for p in populations]))
    assert run(handler, populations, 40) == [19]  # 0.98 m at 5 cm a step: in the 20th
    assert moving.halted == [[2]] and parked.halted == [[0]]
    assert [s.rows.tolist() for s in moving.shoves] == [[2]]
    assert moving.shoves[0].velocities[0, 0] == pytest.approx(-RESTITUTION * 5.0)
    assert moving.shoves[0].velocity_changes[0, 0] == pytest.approx(-(1 + RESTITUTION) * 5.0)
    assert parked.shoves == [] and parked.x.tolist() == [LENGTH_M + 0.98]
