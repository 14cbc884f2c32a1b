"""Sensors keep their last reading for the same inputs (sensors/last_reading.py): a
standing vehicle's IMU and GPS read as a fresh model reads, the sign of a zero counts,
and noise is drawn afresh at every reading."""

from __future__ import annotations

import math

import numpy as np

from egosim.sensors import EgoKinematics, GpsModel, ImuModel, ImuNoise, ImuReading, Pose
from egosim.sensors.last_reading import LastReading
from egosim.world.map import GeoReference

STANDING = EgoKinematics(roll=0.01, pitch=-0.02, yaw=1.3)


def bits(reading: ImuReading) -> bytes:
    return np.array(
        [*reading.orientation, *reading.angular_velocity, *reading.linear_acceleration]
    ).tobytes()


def test_a_repeated_reading_is_the_reading_of_a_fresh_model() -> None:
    model = ImuModel()
    first = model.measure(STANDING)
    assert bits(model.measure(STANDING)) == bits(first) == bits(ImuModel().measure(STANDING))


def test_the_sign_of_a_zero_input_counts() -> None:
    """0.0 == -0.0, yet a sine of either keeps its sign: they are different inputs."""
    last = LastReading[float](1)
    assert last.of((0.0,), lambda: math.sin(0.0)) == 0.0
    negative = last.of((-0.0,), lambda: math.sin(-0.0))
    assert math.copysign(1.0, negative) == -1.0
    assert last.of((-0.0,), lambda: 1.0) is negative  # the same inputs: kept


def test_a_changed_input_gives_a_new_reading() -> None:
    model = ImuModel()
    model.measure(STANDING)
    moving = EgoKinematics(roll=0.01, pitch=-0.02, yaw=1.3, velocity_rate=(1.5, 0.0, 0.0))
    assert bits(model.measure(moving)) == bits(ImuModel().measure(moving))


def test_a_noisy_imu_draws_new_noise_at_every_reading() -> None:
    model = ImuModel(noise=ImuNoise(angular_velocity_std_rad_s=0.01))
    rng = np.random.default_rng(3)
    first, second = model.measure(STANDING, rng), model.measure(STANDING, rng)
    assert first.angular_velocity != second.angular_velocity


def test_a_standing_gps_reads_as_a_fresh_model() -> None:
    georeference = GeoReference(
        utm_zone=52, northern=True, origin_east=313000.0, origin_north=4161000.0, origin_up=0.0
    )
    pose = Pose(x=12.5, y=-40.25, yaw=0.4)
    model = GpsModel(georeference)
    first = model.measure(pose)
    assert model.measure(pose) == first == GpsModel(georeference).measure(pose)
    moved = Pose(x=12.75, y=-40.25, yaw=0.4)
    assert model.measure(moved) == GpsModel(georeference).measure(moved) != first
