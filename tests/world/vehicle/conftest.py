from __future__ import annotations

from collections.abc import Callable, Iterator

import pytest
from tests.world.vehicle import driving

from egosim.world.vehicle import Vehicle, VehicleStatus

Drive = Callable[..., Iterator[VehicleStatus]]


@pytest.fixture
def drive() -> Drive:
    return driving.drive


@pytest.fixture
def niro() -> Vehicle:
    return Vehicle.from_catalogue()
