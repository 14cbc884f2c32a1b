"""Velocity and acceleration modes of CtrlCmd."""

from __future__ import annotations

import pytest

from egosim.world.vehicle import (
    ControlCommand,
    Gear,
    LongitudinalMode,
    Pose,
    RoadSurface,
    Vehicle,
)

KMH = 1.0 / 3.6


@pytest.mark.parametrize("start", [0.0, 50.0 * KMH])
def test_velocity_mode_settles_at_30_kmh_without_overshoot(drive, niro, start) -> None:
    niro.teleport(Pose(), speed=start)
    target = 30.0 * KMH
    command = ControlCommand(mode=LongitudinalMode.VELOCITY, velocity=target)
    speeds = [status.velocity[0] for status in drive(niro, command, seconds=30.0)]
    if start < target:
        assert max(speeds) <= target + 2.0 * KMH
    else:
        assert min(speeds) >= target - 2.0 * KMH
    assert all(abs(speed - target) <= 0.5 * KMH for speed in speeds[-1000:])


def test_velocity_mode_holds_speed_up_a_grade(drive, niro) -> None:
    target = 30.0 * KMH
    command = ControlCommand(mode=LongitudinalMode.VELOCITY, velocity=target)
    uphill = RoadSurface(z=0.0, pitch=-0.05)
    *_, status = drive(niro, command, seconds=30.0, surface=uphill)
    assert status.velocity[0] == pytest.approx(target, abs=0.5 * KMH)


def test_velocity_mode_in_reverse_backs_up_at_the_target(drive) -> None:
    vehicle = Vehicle.from_catalogue(gear=Gear.REVERSE)
    command = ControlCommand(mode=LongitudinalMode.VELOCITY, velocity=1.5)
    *_, status = drive(vehicle, command, seconds=20.0)
    assert status.velocity[0] == pytest.approx(-1.5, abs=0.5 * KMH)


@pytest.mark.parametrize(("start", "target"), [(5.0, 1.5), (20.0, -2.0)])
def test_acceleration_mode_tracks_the_target(drive, niro, start, target) -> None:
    niro.teleport(Pose(), speed=start)
    command = ControlCommand(mode=LongitudinalMode.ACCELERATION, acceleration=target)
    statuses = list(drive(niro, command, seconds=5.0))
    window = statuses[100:]
    for status in window:
        assert status.acceleration[0] == pytest.approx(target, abs=0.05)
    mean = (window[-1].velocity[0] - statuses[99].velocity[0]) / (len(window) * 0.01)
    assert mean == pytest.approx(target, abs=0.02)


def test_acceleration_mode_reports_the_pedals_it_applies(drive, niro) -> None:
    niro.teleport(Pose(), speed=20.0)
    accelerating = ControlCommand(mode=LongitudinalMode.ACCELERATION, acceleration=1.5)
    *_, status = drive(niro, accelerating, seconds=1.0)
    assert 0.0 < status.accel_pedal < 1.0
    assert status.brake_pedal == 0.0
    braking = ControlCommand(mode=LongitudinalMode.ACCELERATION, acceleration=-2.0)
    *_, status = drive(niro, braking, seconds=1.0)
    assert status.accel_pedal == 0.0
    # Drag and rolling resistance give part of the deceleration.
    assert 0.0 < status.brake_pedal < 2.0 / niro.model.max_brake_decel
