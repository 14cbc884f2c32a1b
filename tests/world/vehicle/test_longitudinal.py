"""Braking, gears and grades against closed forms."""

from __future__ import annotations

import math

import pytest

from egosim.world.vehicle import ControlCommand, Gear, Pose, RoadSurface, Vehicle
from egosim.world.vehicle.catalogue import GRAVITY
from egosim.world.vehicle.longitudinal import AIR_DENSITY

FULL_BRAKE = ControlCommand(brake=1.0)
COAST = ControlCommand()
GRADE = math.atan(0.10)
FACING_UPHILL = RoadSurface(z=0.0, pitch=-GRADE)
FACING_DOWNHILL = RoadSurface(z=0.0, pitch=GRADE)


def test_full_brake_from_50_kmh_stops_within_the_configured_deceleration(drive, niro) -> None:
    speed = 50.0 / 3.6
    niro.teleport(Pose(), speed=speed)
    bound = speed**2 / (2.0 * niro.model.max_brake_decel)
    statuses = list(drive(niro, FULL_BRAKE, seconds=5.0))
    stopped = next(status for status in statuses if status.speed == 0.0)
    assert 0.9 * bound <= stopped.pose.x <= bound
    # Held brakes keep the car where it stopped; they never push it backwards.
    assert all(status.velocity[0] >= 0.0 for status in statuses)
    assert statuses[-1].pose.x == stopped.pose.x


def test_brake_never_reverses_a_car_rolling_backwards(drive, niro) -> None:
    niro.teleport(Pose(), speed=-3.0)
    statuses = list(drive(niro, FULL_BRAKE, seconds=2.0))
    assert all(status.velocity[0] <= 0.0 for status in statuses)
    assert statuses[-1].speed == 0.0


@pytest.mark.parametrize("surface", [FACING_UPHILL, FACING_DOWNHILL])
@pytest.mark.parametrize("command", [COAST, ControlCommand(accel=1.0)])
def test_parking_holds_on_a_10_percent_grade(drive, niro, surface, command) -> None:
    niro.set_gear(Gear.PARKING)
    *_, status = drive(niro, command, seconds=10.0, surface=surface)
    assert status.speed == 0.0
    assert (status.pose.x, status.pose.y) == (0.0, 0.0)


def test_neutral_coasts_down_the_grade_with_gravity_less_resistances(drive, niro) -> None:
    niro.set_gear(Gear.NEUTRAL)
    model = niro.model
    speeds = []
    for status in drive(niro, COAST, seconds=10.0, surface=FACING_DOWNHILL):
        vx = status.velocity[0]
        expected = (
            GRAVITY * math.sin(GRADE)
            - model.rolling_resistance_coeff * GRAVITY * math.cos(GRADE)
            - 0.5 * AIR_DENSITY * model.drag_area * vx**2 / model.mass
        )
        assert status.acceleration[0] == pytest.approx(expected, rel=0.01)
        speeds.append(vx)
    assert speeds == sorted(speeds)
    assert speeds[-1] > 5.0


def test_neutral_rolls_backwards_down_the_slope_it_faces(drive, niro) -> None:
    niro.set_gear(Gear.NEUTRAL)
    niro.teleport(Pose(pitch=FACING_UPHILL.pitch))
    *_, status = drive(niro, COAST, seconds=3.0)
    assert status.velocity[0] < -1.0
    # Without a map surface the vehicle follows its own plane: down the slope.
    assert status.pose.x < 0.0
    assert status.pose.z == pytest.approx(status.pose.x * math.tan(GRADE), rel=1e-9)


def test_neutral_ignores_the_accelerator(drive, niro) -> None:
    niro.set_gear(Gear.NEUTRAL)
    *_, status = drive(niro, ControlCommand(accel=1.0), seconds=5.0)
    assert status.speed == 0.0
    assert status.accel_pedal == 1.0


def test_drive_moves_forwards_and_reverse_backwards_at_limited_speed(drive, niro) -> None:
    *_, forwards = drive(niro, ControlCommand(accel=0.3), seconds=3.0)
    assert forwards.velocity[0] > 1.0
    assert forwards.pose.x > 0.0

    reversing = Vehicle.from_catalogue(gear=Gear.REVERSE)
    statuses = list(drive(reversing, ControlCommand(accel=1.0), seconds=20.0))
    assert statuses[10].velocity[0] < 0.0
    assert statuses[-1].pose.x < 0.0
    top_speed = max(status.speed for status in statuses)
    assert top_speed <= reversing.model.max_reverse_speed
    assert statuses[-1].speed == pytest.approx(top_speed, rel=0.05)


def test_power_limits_the_drive_force_at_speed(drive, niro) -> None:
    speed = 30.0
    niro.teleport(Pose(), speed=speed)
    *_, status = drive(niro, ControlCommand(accel=1.0), seconds=0.01)
    model = niro.model
    resistances = (
        model.rolling_resistance_coeff * model.mass * GRAVITY
        + 0.5 * AIR_DENSITY * model.drag_area * speed**2
    )
    expected = (model.max_power / speed - resistances) / model.mass
    assert status.acceleration[0] == pytest.approx(expected, rel=0.01)
