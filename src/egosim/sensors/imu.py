"""Inertial measurement unit: orientation, body rates and specific force.

The accelerometer measures specific force, f = a - g, where a is the inertial
acceleration of the sensor and g = (0, 0, -STANDARD_GRAVITY) in the ENU map
frame; at rest on level ground it reads +STANDARD_GRAVITY on z.

For a sensor mounted at r (base_link, m) the acceleration of the mount point
adds the lever-arm terms of a rigid body:
    a_sensor = a_base + alpha x r + omega x (omega x r)
The mount rotation then turns every body vector into the sensor's axes.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from egosim.sensors.frames import MountPose
from egosim.sensors.noise import gaussian, require_non_negative
from egosim.sensors.rotation import Quaternion, quaternion_from_matrix, rotation_matrix

STANDARD_GRAVITY = 9.80665
"""m/s^2, the conventional standard gravity (CGPM 1901), used everywhere on the map."""

Vector3Tuple = tuple[float, float, float]
Covariance = tuple[float, float, float, float, float, float, float, float, float]


@dataclass(frozen=True)
class EgoKinematics:
    """Motion of base_link. Vectors are in base_link axes (x forward, y left, z up).

    `velocity_rate` is the time derivative of the body-frame velocity
    components (what a vehicle model integrates, e.g. (dv/dt, 0, 0) for a
    bicycle model), without gravity. The inertial acceleration adds the
    transport term omega x velocity, which is the centripetal acceleration of
    a turning vehicle.
    """

    roll: float = 0.0
    pitch: float = 0.0
    yaw: float = 0.0
    velocity: Vector3Tuple = (0.0, 0.0, 0.0)
    """m/s"""
    velocity_rate: Vector3Tuple = (0.0, 0.0, 0.0)
    """m/s^2"""
    angular_velocity: Vector3Tuple = (0.0, 0.0, 0.0)
    """(p, q, r), rad/s"""
    angular_acceleration: Vector3Tuple = (0.0, 0.0, 0.0)
    """rad/s^2, only needed for the lever arm of an off-centre mount"""

    @property
    def inertial_acceleration(self) -> np.ndarray:
        """Acceleration of base_link in an inertial (map) frame, in body axes, m/s^2."""
        return np.add(self.velocity_rate, np.cross(self.angular_velocity, self.velocity))


@dataclass(frozen=True)
class ImuNoise:
    """Per-axis Gaussian noise (std) and constant biases, in sensor axes."""

    orientation_std_rad: float = 0.0
    angular_velocity_std_rad_s: float = 0.0
    linear_acceleration_std_m_s2: float = 0.0
    angular_velocity_bias_rad_s: Vector3Tuple = (0.0, 0.0, 0.0)
    linear_acceleration_bias_m_s2: Vector3Tuple = (0.0, 0.0, 0.0)

    def __post_init__(self) -> None:
        require_non_negative(
            "IMU noise std",
            [
                self.orientation_std_rad,
                self.angular_velocity_std_rad_s,
                self.linear_acceleration_std_m_s2,
            ],
        )


@dataclass(frozen=True)
class ImuReading:
    orientation: Quaternion
    """Sensor frame in the ENU map frame, (x, y, z, w)."""
    angular_velocity: Vector3Tuple
    """Sensor axes, rad/s."""
    linear_acceleration: Vector3Tuple
    """Specific force in sensor axes, m/s^2, gravity included."""
    orientation_covariance: Covariance
    angular_velocity_covariance: Covariance
    linear_acceleration_covariance: Covariance


def _diagonal_covariance(std: float) -> Covariance:
    variance = float(std) ** 2
    return (variance, 0.0, 0.0, 0.0, variance, 0.0, 0.0, 0.0, variance)


def _as_tuple(vector: np.ndarray) -> Vector3Tuple:
    return (float(vector[0]), float(vector[1]), float(vector[2]))


@dataclass(frozen=True)
class ImuModel:
    mount: MountPose = field(default_factory=MountPose)
    noise: ImuNoise = field(default_factory=ImuNoise)

    def measure(
        self, kinematics: EgoKinematics, rng: np.random.Generator | None = None
    ) -> ImuReading:
        """One reading; `rng` is required only when noise std is configured."""
        body_to_map = rotation_matrix(kinematics.roll, kinematics.pitch, kinematics.yaw)
        sensor_to_body = self.mount.rotation
        omega = np.asarray(kinematics.angular_velocity, dtype=np.float64)
        lever = self.mount.translation

        mount_acceleration = (
            kinematics.inertial_acceleration
            + np.cross(kinematics.angular_acceleration, lever)
            + np.cross(omega, np.cross(omega, lever))
        )
        # -g in map axes is straight up; its body components are the map z row of R.
        specific_force = mount_acceleration + STANDARD_GRAVITY * body_to_map[2]

        noise = self.noise
        linear_acceleration = (
            sensor_to_body.T @ specific_force
            + np.asarray(noise.linear_acceleration_bias_m_s2)
            + gaussian(np.full(3, noise.linear_acceleration_std_m_s2), rng, "IMU")
        )
        angular_velocity = (
            sensor_to_body.T @ omega
            + np.asarray(noise.angular_velocity_bias_rad_s)
            + gaussian(np.full(3, noise.angular_velocity_std_rad_s), rng, "IMU")
        )
        attitude_error = gaussian(np.full(3, noise.orientation_std_rad), rng, "IMU")
        sensor_to_map = body_to_map @ sensor_to_body @ rotation_matrix(*attitude_error)

        return ImuReading(
            orientation=quaternion_from_matrix(sensor_to_map),
            angular_velocity=_as_tuple(angular_velocity),
            linear_acceleration=_as_tuple(linear_acceleration),
            orientation_covariance=_diagonal_covariance(noise.orientation_std_rad),
            angular_velocity_covariance=_diagonal_covariance(noise.angular_velocity_std_rad_s),
            linear_acceleration_covariance=_diagonal_covariance(noise.linear_acceleration_std_m_s2),
        )
