"""Driving a vehicle model (car or skid-steer) with one command for a while."""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

from egosim.world.vehicle import RoadSurface, VehicleStatus

STEP = 0.01
"""Simulation step the tests drive with, s."""


def drive(
    vehicle: Any,
    command: Any,
    seconds: float,
    surface: RoadSurface | None = None,
) -> Iterator[VehicleStatus]:
    """Send `command` every step for `seconds`, yielding the status after each step."""
    for _ in range(round(seconds / STEP)):
        vehicle.command(command)
        vehicle.step(STEP, surface)
        yield vehicle.status()
