"""Bit-for-bit repeatability and stability at rest."""

from __future__ import annotations

import math

from egosim.world.vehicle import (
    ControlCommand,
    Gear,
    LongitudinalMode,
    Pose,
    Vehicle,
    VehicleStatus,
)

SCRIPT = [
    (ControlCommand(accel=0.6, front_steer=0.1), 3.0),
    (ControlCommand(mode=LongitudinalMode.VELOCITY, velocity=12.0, front_steer=-0.05), 5.0),
    (ControlCommand(mode=LongitudinalMode.ACCELERATION, acceleration=-2.0, front_steer=0.2), 4.0),
    (ControlCommand(brake=0.5), 3.0),
]


def run_script(drive) -> list[VehicleStatus]:
    vehicle = Vehicle.from_catalogue(pose=Pose(x=10.0, y=-3.0, yaw=0.7))
    trajectory = []
    for command, seconds in SCRIPT:
        trajectory.extend(drive(vehicle, command, seconds))
    vehicle.set_gear(Gear.REVERSE)
    trajectory.extend(drive(vehicle, ControlCommand(accel=0.5, front_steer=0.3), 4.0))
    return trajectory


def test_same_commands_give_identical_trajectories(drive) -> None:
    first, second = run_script(drive), run_script(drive)
    assert first == second
    assert first[-1].pose != first[0].pose


def test_zero_command_for_a_minute_keeps_the_car_at_rest(drive) -> None:
    vehicle = Vehicle.from_catalogue(pose=Pose(x=1.0, y=2.0, yaw=0.3))
    for status in drive(vehicle, ControlCommand(), seconds=60.0):
        assert status.pose == Pose(x=1.0, y=2.0, yaw=0.3)
        assert status.velocity == (0.0, 0.0, 0.0)
        assert status.acceleration == (0.0, 0.0, 0.0)
        assert status.yaw_rate == 0.0


def test_turning_the_wheel_at_rest_does_not_move_the_car(drive) -> None:
    vehicle = Vehicle.from_catalogue()
    *_, status = drive(vehicle, ControlCommand(front_steer=0.5), seconds=10.0)
    assert status.pose == Pose()
    assert status.front_steer == 0.5
    wheels = status.wheels
    for wheel in (wheels.front_left, wheels.front_right, wheels.rear_left, wheels.rear_right):
        assert math.isfinite(wheel.slip_angle)


def test_teleport_sets_pose_speed_and_steering(niro) -> None:
    niro.teleport(Pose(x=5.0, y=6.0, z=1.0, yaw=-1.0), speed=4.0, front_steer=0.1)
    status = niro.status()
    assert status.pose == Pose(x=5.0, y=6.0, z=1.0, yaw=-1.0)
    assert status.velocity[0] == 4.0
    assert status.front_steer == 0.1
    assert status.yaw_rate == 4.0 * math.tan(0.1) / niro.model.wheelbase
