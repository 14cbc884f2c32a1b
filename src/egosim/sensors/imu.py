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

import functools
from dataclasses import dataclass, field

import numpy as np

from egosim.sensors.frames import MountPose, rotation_of
from egosim.sensors.last_reading import LastReading
from egosim.sensors.noise import gaussian, require_non_negative
from egosim.sensors.rotation import Matrix3, Quaternion, quaternion_from_matrix, rotation_matrix
from egosim.sensors.vectors import Vector3Tuple, add3, cross3, floats3

STANDARD_GRAVITY = 9.80665
"""m/s^2, the conventional standard gravity (CGPM 1901), used everywhere on the map."""

NO_ATTITUDE_ERROR = rotation_matrix(0.0, 0.0, 0.0)
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
    def inertial_acceleration(self) -> Vector3Tuple:
        """Acceleration of base_link in an inertial (map) frame, in body axes, m/s^2."""
        return add3(floats3(self.velocity_rate), cross3(self.angular_velocity, self.velocity))


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


# One reading is a handful of 3-vector operations, done 100 times a second: on plain
# floats (sensors/vectors.py). Matrix products stay numpy's: BLAS rounds them its own way.


def _noise(std: float, rng: np.random.Generator | None) -> Vector3Tuple:
    if std == 0.0:  # gaussian() would make the same zeros, through numpy
        return (0.0, 0.0, 0.0)
    return floats3(gaussian(np.full(3, std), rng, "IMU"))


def _rotated(matrix: Matrix3, vector: Vector3Tuple) -> Vector3Tuple:
    x, y, z = (matrix @ np.array(vector)).tolist()
    return (x, y, z)


@dataclass(frozen=True)
class ImuModel:
    mount: MountPose = field(default_factory=MountPose)
    noise: ImuNoise = field(default_factory=ImuNoise)

    @functools.cached_property
    def _sensor_to_body(self) -> Matrix3:
        """The mount's rotation, worked out once rather than for every reading."""
        return rotation_of(self.mount)

    @functools.cached_property
    def _body_to_sensor(self) -> Matrix3:
        turned: Matrix3 = self._sensor_to_body.T
        return turned

    @functools.cached_property
    def _constants(self) -> _ImuConstants:
        """What every reading of this model shares: its lever arm, biases, covariances."""
        mount, noise = self.mount, self.noise
        return _ImuConstants(
            lever=(float(mount.x), float(mount.y), float(mount.z)),
            linear_acceleration_bias=floats3(noise.linear_acceleration_bias_m_s2),
            angular_velocity_bias=floats3(noise.angular_velocity_bias_rad_s),
            orientation_covariance=_diagonal_covariance(noise.orientation_std_rad),
            angular_velocity_covariance=_diagonal_covariance(noise.angular_velocity_std_rad_s),
            linear_acceleration_covariance=_diagonal_covariance(noise.linear_acceleration_std_m_s2),
        )

    @functools.cached_property
    def _noiseless(self) -> bool:
        """Its readings draw no noise (biases are no draw)."""
        noise = self.noise
        return (
            noise.orientation_std_rad
            == noise.angular_velocity_std_rad_s
            == noise.linear_acceleration_std_m_s2
            == 0.0
        )

    @functools.cached_property
    def _last_reading(self) -> LastReading[ImuReading]:
        return LastReading(15)

    def measure(
        self, kinematics: EgoKinematics, rng: np.random.Generator | None = None
    ) -> ImuReading:
        """One reading; `rng` is required only when noise std is configured."""
        if not self._noiseless:
            return self._measure(kinematics, rng)
        k = kinematics
        inputs = (
            k.roll, k.pitch, k.yaw, *k.velocity, *k.velocity_rate,
            *k.angular_velocity, *k.angular_acceleration,
        )  # fmt: skip
        return self._last_reading.of(inputs, lambda: self._measure(kinematics, None))

    def _measure(self, kinematics: EgoKinematics, rng: np.random.Generator | None) -> ImuReading:
        body_to_map = rotation_matrix(kinematics.roll, kinematics.pitch, kinematics.yaw)
        constants, noise = self._constants, self.noise
        omega = floats3(kinematics.angular_velocity)
        lever = constants.lever

        mount_acceleration = add3(
            kinematics.inertial_acceleration,
            cross3(kinematics.angular_acceleration, lever),
            cross3(omega, cross3(omega, lever)),
        )
        # -g in map axes is straight up; its body components are the map z row of R.
        up_x, up_y, up_z = body_to_map[2].tolist()
        specific_force = add3(
            mount_acceleration,
            (STANDARD_GRAVITY * up_x, STANDARD_GRAVITY * up_y, STANDARD_GRAVITY * up_z),
        )

        linear_acceleration = add3(
            _rotated(self._body_to_sensor, specific_force),
            constants.linear_acceleration_bias,
            _noise(noise.linear_acceleration_std_m_s2, rng),
        )
        angular_velocity = add3(
            _rotated(self._body_to_sensor, omega),
            constants.angular_velocity_bias,
            _noise(noise.angular_velocity_std_rad_s, rng),
        )
        if noise.orientation_std_rad == 0.0:  # the zero error _noise gives, turned once
            attitude_error = NO_ATTITUDE_ERROR
        else:
            attitude_error = rotation_matrix(*_noise(noise.orientation_std_rad, rng))
        sensor_to_map = body_to_map @ self._sensor_to_body @ attitude_error

        return ImuReading(
            orientation=quaternion_from_matrix(sensor_to_map),
            angular_velocity=angular_velocity,
            linear_acceleration=linear_acceleration,
            orientation_covariance=constants.orientation_covariance,
            angular_velocity_covariance=constants.angular_velocity_covariance,
            linear_acceleration_covariance=constants.linear_acceleration_covariance,
        )


@dataclass(frozen=True)
class _ImuConstants:
    lever: Vector3Tuple
    linear_acceleration_bias: Vector3Tuple
    angular_velocity_bias: Vector3Tuple
    orientation_covariance: Covariance
    angular_velocity_covariance: Covariance
    linear_acceleration_covariance: Covariance
