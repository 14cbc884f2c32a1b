"""A vehicle's reported pose is MORAI's vehicle origin: the midpoint of the rear axle."""

from __future__ import annotations

import math

import numpy as np
import pytest

from egosim.world.vehicle import ControlCommand, LongitudinalMode, Pose, Vehicle


def _circle(points: np.ndarray) -> tuple[float, float, float]:
    """Least-squares circle (centre x, centre y, radius) through (N, 2) points."""
    x, y = points[:, 0], points[:, 1]
    a = np.column_stack((2 * x, 2 * y, np.ones(len(x))))
    (cx, cy, c), *_ = np.linalg.lstsq(a, x * x + y * y, rcond=None)
    return float(cx), float(cy), math.sqrt(c + cx * cx + cy * cy)


@pytest.mark.parametrize("steer", [0.1, 0.3, 0.5])
def test_constant_steer_traces_the_rear_axle_circle_of_radius_wheelbase_over_tan_steer(
    niro: Vehicle, steer: float
) -> None:
    # Below 1 m/s the motion is the kinematic bicycle's: both axles roll without slip.
    niro.teleport(Pose(), speed=0.8, front_steer=steer)
    niro.command(ControlCommand(mode=LongitudinalMode.VELOCITY, velocity=0.8, front_steer=steer))
    points = []
    for _ in range(4000):
        niro.step(0.01)
        pose = niro.status().pose
        points.append((pose.x, pose.y))
    cx, cy, radius = _circle(np.array(points[1000:]))
    wheelbase = niro.model.wheelbase
    turning_radius = wheelbase / math.tan(steer)
    assert radius == pytest.approx(turning_radius, rel=1e-3)
    # Started at the origin facing east: the centre lies on the rear axle's line, left.
    assert (cx, cy) == pytest.approx((0.0, turning_radius), abs=1e-3 * turning_radius)
    # The CG would run on a wider circle: the test tells the two points apart.
    cg_radius = math.hypot(turning_radius, niro.model.cg_to_rear_axle)
    assert cg_radius != pytest.approx(radius, rel=1e-3)
    # The rear axle moves along the body's x axis: no lateral velocity.
    assert niro.status().velocity[1] == pytest.approx(0.0, abs=1e-9)


def test_teleport_and_status_speak_of_the_same_point(niro: Vehicle) -> None:
    pose = Pose(x=12.0, y=-3.0, z=0.5, yaw=0.7)
    niro.teleport(pose, speed=5.0)
    status = niro.status().pose
    assert (status.x, status.y, status.z, status.yaw) == pytest.approx((12.0, -3.0, 0.5, 0.7))
