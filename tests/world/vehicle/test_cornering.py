"""Steady-state cornering against the linear single-track closed form."""

from __future__ import annotations

import math
from dataclasses import replace

import pytest

from egosim.world.vehicle import ControlCommand, LongitudinalMode, Pose, Vehicle, VehicleModel
from egosim.world.vehicle.catalogue import vehicle_model


def understeer_gradient(model: VehicleModel) -> float:
    """K (s²/m) in r = v·(δf − δr)/(L + K·v²)."""
    a, b = model.cg_to_front_axle, model.cg_to_rear_axle
    cf, cr = model.cornering_stiffness_front, model.cornering_stiffness_rear
    return model.mass * (b * cr - a * cf) / (model.wheelbase * cf * cr)


def four_wheel_steer(model: VehicleModel) -> VehicleModel:
    return replace(model, max_steer_rear=0.1)


@pytest.mark.parametrize(
    ("model_name", "speed", "front_steer", "rear_steer"),
    [
        ("2016_Kia_Niro(HEV)", 10.0, 0.02, 0.0),
        ("2016_Kia_Niro(HEV)", 20.0, -0.01, 0.0),
        ("2016_Kia_Niro(HEV)", 10.0, 0.02, -0.01),
        ("2019_Hyundai_Universe", 10.0, 0.03, 0.0),
    ],
)
def test_steady_state_yaw_rate_and_radius_match_closed_form(
    drive, model_name: str, speed: float, front_steer: float, rear_steer: float
) -> None:
    model = four_wheel_steer(vehicle_model(model_name))
    vehicle = Vehicle(model, Pose(), max_substep=0.01)
    vehicle.teleport(Pose(), speed=speed)
    command = ControlCommand(
        mode=LongitudinalMode.VELOCITY,
        velocity=speed,
        front_steer=front_steer,
        rear_steer=rear_steer,
    )
    *_, status = drive(vehicle, command, seconds=30.0)

    vx = status.velocity[0]
    expected_yaw_rate = (
        vx * (front_steer - rear_steer) / (model.wheelbase + understeer_gradient(model) * vx**2)
    )
    assert status.yaw_rate == pytest.approx(expected_yaw_rate, rel=0.02)
    radius = status.speed / status.yaw_rate
    assert radius == pytest.approx(vx / expected_yaw_rate, rel=0.02)
    # In a steady turn the CG accelerates only centripetally.
    assert status.acceleration[1] == pytest.approx(vx * status.yaw_rate, rel=1e-6)


def test_path_is_a_circle_of_the_steady_state_radius(drive) -> None:
    vehicle = Vehicle.from_catalogue()
    vehicle.teleport(Pose(), speed=10.0)
    command = ControlCommand(mode=LongitudinalMode.VELOCITY, velocity=10.0, front_steer=0.05)
    statuses = list(drive(vehicle, command, seconds=40.0))
    radius = statuses[-1].speed / statuses[-1].yaw_rate
    # Centre of the circle from the last pose: radius to the left of the velocity.
    last = statuses[-1].pose
    heading = last.yaw + math.atan2(statuses[-1].velocity[1], statuses[-1].velocity[0])
    centre = (last.x - radius * math.sin(heading), last.y + radius * math.cos(heading))
    for status in statuses[-1000:]:
        distance = math.hypot(status.pose.x - centre[0], status.pose.y - centre[1])
        assert distance == pytest.approx(radius, rel=0.002)


@pytest.mark.parametrize("rear_steer", [0.0, -0.1])
def test_low_speed_turn_is_kinematic(drive, rear_steer: float) -> None:
    model = four_wheel_steer(vehicle_model("2016_Kia_Niro(HEV)"))
    vehicle = Vehicle(model)
    front_steer = 0.4
    command = ControlCommand(
        mode=LongitudinalMode.VELOCITY, velocity=0.5, front_steer=front_steer, rear_steer=rear_steer
    )
    *_, status = drive(vehicle, command, seconds=20.0)
    vx = status.velocity[0]
    assert vx == pytest.approx(0.5, abs=1e-3)
    assert status.yaw_rate == pytest.approx(
        vx * (math.tan(front_steer) - math.tan(rear_steer)) / model.wheelbase, rel=1e-9
    )


def test_steering_moves_at_the_actuator_rate(drive, niro: Vehicle) -> None:
    target = niro.model.max_steer_front
    command = ControlCommand(mode=LongitudinalMode.PEDALS, front_steer=target)
    statuses = list(drive(niro, command, seconds=0.5))
    assert statuses[-1].front_steer == pytest.approx(niro.model.max_steer_rate * 0.5)
    *_, settled = drive(niro, command, seconds=3.0)
    assert settled.front_steer == pytest.approx(target)
