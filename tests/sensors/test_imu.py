"""IMU readings against rigid-body kinematics and gravity."""

from __future__ import annotations

import numpy as np
import pytest

from egosim.sensors import STANDARD_GRAVITY, EgoKinematics, ImuModel, ImuNoise, MountPose
from egosim.sensors.errors import MissingRandomGeneratorError
from tests.sensors.geometry import matrix_from_quaternion

G = 9.80665


def test_at_rest_on_level_ground_reads_gravity_up() -> None:
    reading = ImuModel().measure(EgoKinematics())
    assert STANDARD_GRAVITY == G
    np.testing.assert_allclose(reading.linear_acceleration, (0.0, 0.0, G), atol=1e-12)
    np.testing.assert_allclose(reading.angular_velocity, 0.0, atol=1e-15)
    np.testing.assert_allclose(reading.orientation, (0.0, 0.0, 0.0, 1.0), atol=1e-15)


@pytest.mark.parametrize(
    ("roll", "pitch", "yaw"), [(0.2, 0.0, 0.0), (0.0, 0.1, 1.0), (0.2, -0.3, -2.0)]
)
def test_tilted_vehicle_sees_gravity_rotated(roll: float, pitch: float, yaw: float) -> None:
    reading = ImuModel().measure(EgoKinematics(roll=roll, pitch=pitch, yaw=yaw))
    # The reaction to gravity points up; in body axes that is the map's z axis seen from the body.
    expected = G * np.array(
        [-np.sin(pitch), np.cos(pitch) * np.sin(roll), np.cos(pitch) * np.cos(roll)]
    )
    np.testing.assert_allclose(reading.linear_acceleration, expected, atol=1e-12)
    assert np.linalg.norm(reading.linear_acceleration) == pytest.approx(G)


def test_orientation_follows_attitude() -> None:
    reading = ImuModel().measure(EgoKinematics(yaw=0.7))
    np.testing.assert_allclose(reading.orientation, (0.0, 0.0, np.sin(0.35), np.cos(0.35)))


def test_nose_down_pitch_reads_gravity_on_negative_x() -> None:
    reading = ImuModel().measure(EgoKinematics(pitch=np.pi / 2))
    np.testing.assert_allclose(reading.linear_acceleration, (-G, 0.0, 0.0), atol=1e-12)


def test_yaw_rate_appears_on_z_rate() -> None:
    reading = ImuModel().measure(EgoKinematics(angular_velocity=(0.0, 0.0, 0.3)))
    np.testing.assert_allclose(reading.angular_velocity, (0.0, 0.0, 0.3))
    np.testing.assert_allclose(reading.linear_acceleration, (0.0, 0.0, G), atol=1e-12)


def test_forward_acceleration_appears_on_x() -> None:
    reading = ImuModel().measure(EgoKinematics(velocity=(5.0, 0, 0), velocity_rate=(2.0, 0, 0)))
    np.testing.assert_allclose(reading.linear_acceleration, (2.0, 0.0, G), atol=1e-12)


def test_steady_left_turn_reads_centripetal_acceleration_to_the_left() -> None:
    speed, yaw_rate = 10.0, 0.2
    reading = ImuModel().measure(
        EgoKinematics(velocity=(speed, 0, 0), angular_velocity=(0, 0, yaw_rate))
    )
    np.testing.assert_allclose(reading.linear_acceleration, (0.0, speed * yaw_rate, G), atol=1e-12)


def test_mount_rotation_expresses_vectors_in_sensor_axes() -> None:
    # Sensor turned a quarter turn left: its +x is the body's +y, its -y the body's +x.
    model = ImuModel(mount=MountPose(yaw=np.pi / 2))
    reading = model.measure(
        EgoKinematics(velocity_rate=(2.0, 0, 0), angular_velocity=(0.1, 0, 0), yaw=0.3)
    )
    np.testing.assert_allclose(reading.linear_acceleration, (0.0, -2.0, G), atol=1e-12)
    np.testing.assert_allclose(reading.angular_velocity, (0.0, -0.1, 0.0), atol=1e-15)
    sensor_x_in_map = matrix_from_quaternion(*reading.orientation)[:, 0]
    np.testing.assert_allclose(
        sensor_x_in_map, (np.cos(0.3 + np.pi / 2), np.sin(0.3 + np.pi / 2), 0)
    )


def test_lever_arm_adds_centripetal_and_tangential_terms() -> None:
    yaw_rate, yaw_acceleration, arm = 0.5, 0.2, 2.0
    model = ImuModel(mount=MountPose(x=arm))
    reading = model.measure(
        EgoKinematics(
            angular_velocity=(0, 0, yaw_rate), angular_acceleration=(0, 0, yaw_acceleration)
        )
    )
    # A point 2 m ahead of a yawing base accelerates towards it and sideways.
    np.testing.assert_allclose(
        reading.linear_acceleration,
        (-(yaw_rate**2) * arm, yaw_acceleration * arm, G),
        atol=1e-12,
    )


def test_covariances_are_diagonal_variances_of_the_noise() -> None:
    noise = ImuNoise(
        orientation_std_rad=0.01,
        angular_velocity_std_rad_s=0.002,
        linear_acceleration_std_m_s2=0.05,
    )
    reading = ImuModel(noise=noise).measure(EgoKinematics(), np.random.default_rng(1))
    for covariance, std in [
        (reading.orientation_covariance, 0.01),
        (reading.angular_velocity_covariance, 0.002),
        (reading.linear_acceleration_covariance, 0.05),
    ]:
        np.testing.assert_allclose(np.reshape(covariance, (3, 3)), np.eye(3) * std**2)


def test_noise_and_bias_statistics() -> None:
    noise = ImuNoise(
        angular_velocity_std_rad_s=0.01,
        linear_acceleration_std_m_s2=0.1,
        angular_velocity_bias_rad_s=(0.0, 0.0, 0.02),
        linear_acceleration_bias_m_s2=(0.3, 0.0, 0.0),
    )
    model = ImuModel(noise=noise)
    rng = np.random.default_rng(11)
    readings = [model.measure(EgoKinematics(), rng) for _ in range(4000)]
    rates = np.array([r.angular_velocity for r in readings])
    forces = np.array([r.linear_acceleration for r in readings])
    np.testing.assert_allclose(rates.mean(axis=0), (0.0, 0.0, 0.02), atol=0.001)
    np.testing.assert_allclose(forces.mean(axis=0), (0.3, 0.0, G), atol=0.01)
    np.testing.assert_allclose(rates.std(axis=0), 0.01, rtol=0.05)
    np.testing.assert_allclose(forces.std(axis=0), 0.1, rtol=0.05)


def test_orientation_noise_keeps_a_unit_quaternion_near_truth() -> None:
    model = ImuModel(noise=ImuNoise(orientation_std_rad=0.01))
    reading = model.measure(EgoKinematics(yaw=1.0), np.random.default_rng(5))
    assert np.linalg.norm(reading.orientation) == pytest.approx(1.0)
    truth = np.array([0.0, 0.0, np.sin(0.5), np.cos(0.5)])
    angle = 2 * np.arccos(min(1.0, abs(float(np.dot(reading.orientation, truth)))))
    assert 0.0 < angle < 0.1


def test_noisy_imu_needs_a_generator() -> None:
    with pytest.raises(MissingRandomGeneratorError):
        ImuModel(noise=ImuNoise(linear_acceleration_std_m_s2=0.1)).measure(EgoKinematics())
