"""Per-wheel forces, loads, slip angles and cornering stiffnesses."""

from __future__ import annotations

import pytest

from egosim.world.vehicle import ControlCommand, LongitudinalMode, Pose, VehicleStatus
from egosim.world.vehicle.catalogue import GRAVITY


@pytest.fixture
def left_turn(drive, niro) -> VehicleStatus:
    niro.teleport(Pose(), speed=15.0)
    command = ControlCommand(mode=LongitudinalMode.VELOCITY, velocity=15.0, front_steer=0.03)
    *_, status = drive(niro, command, seconds=20.0)
    assert status.yaw_rate > 0.0
    return status


def _cg_velocity(status: VehicleStatus, vehicle) -> tuple[float, float]:
    """The CG's body velocity: the status reports the rear axle's, whose lateral speed
    lacks the b·r the CG, b ahead of it, has."""
    vx, vy, _ = status.velocity
    return vx, vy + vehicle.model.cg_to_rear_axle * status.yaw_rate


def test_axle_forces_are_what_the_steady_turn_needs(left_turn, niro) -> None:
    model = niro.model
    wheels = left_turn.wheels
    lateral = model.mass * left_turn.acceleration[1]
    front = wheels.front_left.lateral_force + wheels.front_right.lateral_force
    rear = wheels.rear_left.lateral_force + wheels.rear_right.lateral_force
    # No yaw acceleration: the axles share m·ay inversely to their distance from the CG.
    assert front == pytest.approx(lateral * model.cg_to_rear_axle / model.wheelbase, rel=1e-6)
    assert rear == pytest.approx(lateral * model.cg_to_front_axle / model.wheelbase, rel=1e-6)


def test_axle_forces_are_the_linear_tyre_forces(left_turn, niro) -> None:
    model = niro.model
    wheels = left_turn.wheels
    r = left_turn.yaw_rate
    vx, vy = _cg_velocity(left_turn, niro)
    front_slip = left_turn.front_steer - (vy + model.cg_to_front_axle * r) / vx
    rear_slip = -(vy - model.cg_to_rear_axle * r) / vx
    front = wheels.front_left.lateral_force + wheels.front_right.lateral_force
    rear = wheels.rear_left.lateral_force + wheels.rear_right.lateral_force
    assert front == pytest.approx(model.cornering_stiffness_front * front_slip, rel=1e-6)
    assert rear == pytest.approx(model.cornering_stiffness_rear * rear_slip, rel=1e-6)


def test_wheel_stiffnesses_and_loads_sum_to_the_axle(left_turn, niro) -> None:
    model = niro.model
    wheels = left_turn.wheels
    assert wheels.front_left.cornering_stiffness + wheels.front_right.cornering_stiffness == (
        pytest.approx(model.cornering_stiffness_front)
    )
    assert wheels.rear_left.cornering_stiffness + wheels.rear_right.cornering_stiffness == (
        pytest.approx(model.cornering_stiffness_rear)
    )
    loads = [wheels.front_left, wheels.front_right, wheels.rear_left, wheels.rear_right]
    assert sum(wheel.vertical_load for wheel in loads) == pytest.approx(model.mass * GRAVITY)
    assert wheels.front_left.vertical_load + wheels.front_right.vertical_load == pytest.approx(
        model.mass * GRAVITY * model.cg_to_rear_axle / model.wheelbase
    )


def test_outer_wheels_carry_the_load_transfer_and_more_force(left_turn, niro) -> None:
    model = niro.model
    wheels = left_turn.wheels
    transfer = (
        wheels.front_right.vertical_load
        + wheels.rear_right.vertical_load
        - wheels.front_left.vertical_load
        - wheels.rear_left.vertical_load
    )
    expected = model.mass * left_turn.acceleration[1] * model.cg_height / model.track_width
    assert transfer == pytest.approx(expected, rel=1e-9)
    assert wheels.front_right.lateral_force > wheels.front_left.lateral_force > 0.0
    assert wheels.rear_right.lateral_force > wheels.rear_left.lateral_force > 0.0
    assert wheels.front_right.cornering_stiffness > wheels.front_left.cornering_stiffness


def test_slip_angles_use_each_wheels_own_velocity(left_turn, niro) -> None:
    model = niro.model
    wheels = left_turn.wheels
    r = left_turn.yaw_rate
    vx, vy = _cg_velocity(left_turn, niro)
    half_track = model.track_width / 2.0
    a = model.cg_to_front_axle
    # Small angles: slip = steer − lateral / longitudinal velocity of the wheel centre.
    outer = left_turn.front_steer - (vy + r * a) / (vx + r * half_track)
    inner = left_turn.front_steer - (vy + r * a) / (vx - r * half_track)
    assert wheels.front_right.slip_angle == pytest.approx(outer, rel=1e-3)
    assert wheels.front_left.slip_angle == pytest.approx(inner, rel=1e-3)
    assert wheels.front_left.slip_angle != wheels.front_right.slip_angle


def test_standing_car_has_no_lateral_force_or_slip(niro) -> None:
    niro.step(0.1)
    wheels = niro.status().wheels
    for wheel in (wheels.front_left, wheels.front_right, wheels.rear_left, wheels.rear_right):
        assert wheel.lateral_force == 0.0
        assert wheel.slip_angle == 0.0
