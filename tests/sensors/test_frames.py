"""Rotations, poses and the tf transforms map -> base_link -> sensor."""

from __future__ import annotations

import numpy as np
import pytest

from egosim.sensors import MountPose, Pose, base_link_to_sensor, map_to_base_link, sensor_in_map
from egosim.sensors.rotation import quaternion_from_euler, quaternion_from_matrix, rotation_matrix
from tests.sensors.geometry import axis_rotation, matrix_from_quaternion


def test_rotation_matrix_is_yaw_after_pitch_after_roll() -> None:
    roll, pitch, yaw = 0.3, -0.4, 2.1
    expected = axis_rotation(2, yaw) @ axis_rotation(1, pitch) @ axis_rotation(0, roll)
    np.testing.assert_allclose(rotation_matrix(roll, pitch, yaw), expected, atol=1e-15)


@pytest.mark.parametrize(
    ("roll", "pitch", "yaw"),
    [
        (0.0, 0.0, 0.0),
        (0.3, -0.4, 2.1),
        (np.pi - 0.01, 0.0, 0.0),  # near half turns exercise every branch
        (0.0, np.pi / 2 - 0.01, np.pi),
        (0.0, 0.0, np.pi - 0.01),
        (-2.5, 1.2, -3.0),
    ],
)
def test_quaternion_represents_the_same_rotation(roll: float, pitch: float, yaw: float) -> None:
    quaternion = quaternion_from_euler(roll, pitch, yaw)
    assert np.linalg.norm(quaternion) == pytest.approx(1.0, abs=1e-12)
    assert quaternion[3] >= 0.0
    np.testing.assert_allclose(
        matrix_from_quaternion(*quaternion), rotation_matrix(roll, pitch, yaw), atol=1e-12
    )


def test_quarter_turn_about_z_quaternion() -> None:
    half = np.sqrt(0.5)
    np.testing.assert_allclose(
        quaternion_from_matrix(axis_rotation(2, np.pi / 2)), (0, 0, half, half)
    )


def test_map_to_base_link_carries_vehicle_pose() -> None:
    transform = map_to_base_link(Pose(x=10.0, y=-5.0, z=0.2, yaw=np.pi / 2))
    assert (transform.parent_frame, transform.child_frame) == ("map", "base_link")
    assert transform.translation == (10.0, -5.0, 0.2)
    half = np.sqrt(0.5)
    np.testing.assert_allclose(transform.rotation, (0.0, 0.0, half, half), atol=1e-15)


def test_base_link_to_sensor_carries_mount() -> None:
    transform = base_link_to_sensor(MountPose(x=1.2, z=1.6, pitch=0.1), "lidar")
    assert (transform.parent_frame, transform.child_frame) == ("base_link", "lidar")
    assert transform.translation == (1.2, 0.0, 1.6)
    np.testing.assert_allclose(transform.rotation, (0.0, np.sin(0.05), 0.0, np.cos(0.05)))


def test_sensor_in_map_rotates_mount_offset_with_vehicle() -> None:
    origin, rotation = sensor_in_map(
        Pose(x=100.0, y=50.0, z=1.0, yaw=np.pi / 2), MountPose(x=2.0, y=0.5, z=1.5, yaw=np.pi / 2)
    )
    # Facing north, forward is +y and left is -x.
    np.testing.assert_allclose(origin, (99.5, 52.0, 2.5), atol=1e-12)
    # Two quarter turns: the sensor's x axis points west.
    np.testing.assert_allclose(rotation @ (1.0, 0.0, 0.0), (-1.0, 0.0, 0.0), atol=1e-12)
