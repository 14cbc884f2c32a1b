from __future__ import annotations

from collections.abc import Callable, Iterator

import pytest

from egosim.world.vehicle import ControlCommand, RoadSurface, Vehicle, VehicleStatus

STEP = 0.01
"""Simulation step the tests drive with, s."""

Drive = Callable[..., Iterator[VehicleStatus]]


def _drive(
    vehicle: Vehicle,
    command: ControlCommand,
    seconds: float,
    surface: RoadSurface | None = None,
) -> Iterator[VehicleStatus]:
    """Send `command` every step for `seconds`, yielding the status after each step."""
    for _ in range(round(seconds / STEP)):
        vehicle.command(command)
        vehicle.step(STEP, surface)
        yield vehicle.status()


@pytest.fixture
def drive() -> Drive:
    return _drive


@pytest.fixture
def niro() -> Vehicle:
    return Vehicle.from_catalogue()
