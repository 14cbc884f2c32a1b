"""The models MORAI's contest and tutorial stacks drive (ERP42, Ioniq 5) and MORAI's
DataIDs for vehicles and obstacles."""

from __future__ import annotations

import math

import numpy as np
import pytest
from tests.world.vehicle.driving import drive

from egosim.world.traffic import MORAI_OBSTACLE_DATA_IDS, OBSTACLE_MODELS, obstacle_for_data_id
from egosim.world.vehicle import (
    MORAI_VEHICLE_DATA_IDS,
    VEHICLE_CATALOGUE,
    ControlCommand,
    LongitudinalMode,
    Pose,
    Vehicle,
    model_for_data_id,
    vehicle_model,
)

ERP42_TOP_SPEED = 25.0 / 3.6


def test_the_erp42_has_its_published_size_and_limits() -> None:
    erp = vehicle_model("ERP42")
    assert (erp.length, erp.width, erp.wheelbase) == (2.020, 1.160, 1.040)
    assert math.degrees(erp.max_steer_front) == pytest.approx(28.0)
    assert erp.max_speed == pytest.approx(ERP42_TOP_SPEED)


def test_the_ioniq5_has_morais_wheelbase_and_wheel_angle() -> None:
    ioniq = vehicle_model("2023_Hyundai_Ioniq5")
    assert (ioniq.length, ioniq.width, ioniq.wheelbase) == (4.635, 1.890, 3.000)
    assert math.degrees(ioniq.max_steer_front) == pytest.approx(40.0)


@pytest.mark.parametrize(
    "command",
    [
        ControlCommand(accel=1.0),
        # The WeGo ERP42 planner's cruise: 55 km/h asked of a platform capped at 25.
        ControlCommand(mode=LongitudinalMode.VELOCITY, velocity=55.0 / 3.6),
    ],
    ids=["full throttle", "velocity 55 km/h"],
)
def test_the_erp42_never_drives_faster_than_its_governed_top_speed(command) -> None:
    erp = Vehicle.from_catalogue("ERP42")
    speeds = [status.speed for status in drive(erp, command, seconds=30.0)]
    assert max(speeds) <= ERP42_TOP_SPEED + 1e-9
    assert speeds[-1] == pytest.approx(ERP42_TOP_SPEED, abs=0.5 / 3.6)


def test_from_its_top_speed_the_erp42_stops_within_its_braking_distance() -> None:
    erp = Vehicle.from_catalogue("ERP42")
    erp.teleport(Pose(), speed=ERP42_TOP_SPEED)
    statuses = list(drive(erp, ControlCommand(brake=1.0), seconds=5.0))
    stopped = next(status for status in statuses if status.speed == 0.0)
    bound = ERP42_TOP_SPEED**2 / (2.0 * erp.model.max_brake_decel)
    assert 0.9 * bound <= stopped.pose.x <= bound


def test_at_full_lock_the_erp42_circles_on_wheelbase_over_tan_28_degrees() -> None:
    erp = Vehicle.from_catalogue("ERP42")
    lock = math.radians(28.0)
    erp.teleport(Pose(), speed=0.8, front_steer=lock)
    # A command past the lock is held at it.
    command = ControlCommand(mode=LongitudinalMode.VELOCITY, velocity=0.8, front_steer=1.0)
    points = [(s.pose.x, s.pose.y) for s in drive(erp, command, seconds=40.0)]
    assert erp.status().front_steer == pytest.approx(lock)
    # Below 1 m/s the motion is the kinematic bicycle's: the rear axle rolls on a circle.
    radius = 1.040 / math.tan(lock)
    assert fitted_radius(np.array(points[1000:])) == pytest.approx(radius, rel=1e-3)


def fitted_radius(points: np.ndarray) -> float:
    """Radius of the least-squares circle through (N, 2) points."""
    x, y = points[:, 0], points[:, 1]
    a = np.column_stack((2 * x, 2 * y, np.ones(len(x))))
    (cx, cy, c), *_ = np.linalg.lstsq(a, x * x + y * y, rcond=None)
    return math.sqrt(c + cx * cx + cy * cy)


def test_every_vehicle_data_id_names_a_catalogue_model() -> None:
    for data_id, name in MORAI_VEHICLE_DATA_IDS.items():
        assert model_for_data_id(data_id) is VEHICLE_CATALOGUE[name]
    # The ego of MORAI-EDU's K-City tutorial scenario.
    assert model_for_data_id(20200003) is vehicle_model("2016_Kia_Niro(HEV)")
    assert model_for_data_id(99999999) is None


def test_every_obstacle_data_id_is_an_obstacle_model_or_a_parked_car() -> None:
    for data_id, name in MORAI_OBSTACLE_DATA_IDS.items():
        box = obstacle_for_data_id(data_id)
        assert box is not None and box.name == name
        if name not in OBSTACLE_MODELS:
            car = VEHICLE_CATALOGUE[name]
            assert (box.length, box.width, box.height) == (car.length, car.width, car.height)
            assert box.mass_kg is None  # a parked car does not give
    assert obstacle_for_data_id(40100005) is OBSTACLE_MODELS["Cone"]
    assert obstacle_for_data_id(12345) is None
