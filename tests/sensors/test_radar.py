"""The radar against closed-form geometry: positions, azimuths, range rates, areas."""

from __future__ import annotations

import math

import numpy as np
import pytest

from egosim.sensors import MountPose
from egosim.sensors.errors import MissingRandomGeneratorError
from egosim.sensors.radar import RadarConfig, RadarModel, RadarNoise
from egosim.world.traffic.objects import ObjectTable, ObjectType
from egosim.world.vehicle import Pose
from tests.sensors.camera_world import objects

MOUNT = MountPose(x=2.0, z=0.5)
CAR = (4.0, 2.0, 1.5)


def moving(table: ObjectTable, velocities: list[tuple[float, float, float]]) -> ObjectTable:
    return ObjectTable(
        table.unique_ids,
        table.object_types,
        table.names,
        table.positions,
        table.headings,
        np.array(velocities, dtype=np.float64),
        table.accelerations,
        table.sizes,
    )


def test_a_car_ahead_closing_in() -> None:
    radar = RadarModel(RadarConfig(mount=MOUNT))
    # A car 30 m ahead of the sensor, box centre at the sensor's height, driving at us.
    table = moving(
        objects((7, ObjectType.NPC_VEHICLE, (32.0, 0.0, -0.25), math.pi, CAR)), [(-5.0, 0.0, 0.0)]
    )
    found = radar.detect(Pose(), (10.0, 0.0, 0.0), 0.0, table)
    assert found.unique_ids.tolist() == [7]
    assert found.positions[0] == pytest.approx([30.0, 0.0, 0.0])
    assert found.azimuths[0] == pytest.approx(0.0)
    assert found.range_rates[0] == pytest.approx(-15.0)
    # Seen head-on: its width times its height.
    assert found.amplitudes[0] == pytest.approx(10 * math.log10(2.0 * 1.5))


def test_azimuth_and_position_turn_with_the_vehicle_and_the_mount() -> None:
    radar = RadarModel(RadarConfig(mount=MountPose(x=0.0, z=0.0, yaw=math.radians(10.0))))
    pose = Pose(x=100.0, y=50.0, yaw=math.radians(30.0))
    bearing = math.radians(30.0 + 25.0)
    centre = (100.0 + 20.0 * math.cos(bearing), 50.0 + 20.0 * math.sin(bearing), -0.75)
    # A car broadside to the line of sight: its length times its height.
    table = objects((3, ObjectType.NPC_VEHICLE, centre, bearing + math.pi / 2, CAR))
    found = radar.detect(pose, (0.0, 0.0, 0.0), 0.0, table)
    assert math.degrees(found.azimuths[0]) == pytest.approx(15.0)
    expected = 20.0 * np.array([math.cos(math.radians(15)), math.sin(math.radians(15)), 0.0])
    assert found.positions[0] == pytest.approx(expected)
    assert found.amplitudes[0] == pytest.approx(10 * math.log10(4.0 * 1.5))


def test_only_objects_inside_the_fov_and_range_nearest_first_up_to_the_limit() -> None:
    config = RadarConfig(
        mount=MountPose(), horizontal_fov_deg=60.0, max_range_m=100.0, max_detections=2
    )
    table = objects(
        (1, ObjectType.OBSTACLE, (50.0, 0.0, -0.75), 0.0, CAR),  # ahead, 50 m
        (2, ObjectType.OBSTACLE, (20.0, 20.0, -0.75), 0.0, CAR),  # 45 deg: outside 60 deg
        (3, ObjectType.OBSTACLE, (-20.0, 0.0, -0.75), 0.0, CAR),  # behind
        (4, ObjectType.OBSTACLE, (150.0, 0.0, -0.75), 0.0, CAR),  # beyond range
        (5, ObjectType.PEDESTRIAN, (10.0, 2.0, -0.75), 0.0, CAR),  # ahead, nearer
        (6, ObjectType.OBSTACLE, (80.0, 0.0, -0.75), 0.0, CAR),  # ahead, farther: over the limit
        (9, ObjectType.EGO, (0.0, 0.0, -0.75), 0.0, CAR),  # the carrier
    )
    found = RadarModel(config).detect(Pose(), (0.0, 0.0, 0.0), 0.0, table, hidden_ids=(9,))
    assert found.unique_ids.tolist() == [5, 1]


def test_the_yaw_rate_lever_arm_adds_to_the_range_rate() -> None:
    # A sensor 2 m ahead of a vehicle turning at 0.5 rad/s moves left at 1 m/s; an object
    # straight to its left sees it approach at 1 m/s.
    config = RadarConfig(mount=MountPose(x=2.0), horizontal_fov_deg=360.0)
    table = objects((1, ObjectType.OBSTACLE, (2.0, 10.0, -0.75), 0.0, CAR))
    found = RadarModel(config).detect(Pose(), (0.0, 0.0, 0.0), 0.5, table)
    assert found.range_rates[0] == pytest.approx(-1.0)


def test_noise_needs_a_generator_and_is_reproducible() -> None:
    config = RadarConfig(mount=MountPose(), noise=RadarNoise(range_std_m=0.5, azimuth_std_rad=0.01))
    table = objects((1, ObjectType.OBSTACLE, (30.0, 0.0, -0.75), 0.0, CAR))
    with pytest.raises(MissingRandomGeneratorError):
        RadarModel(config).detect(Pose(), (0.0, 0.0, 0.0), 0.0, table)
    first = RadarModel(config).detect(Pose(), (0, 0, 0), 0.0, table, rng=np.random.default_rng(1))
    again = RadarModel(config).detect(Pose(), (0, 0, 0), 0.0, table, rng=np.random.default_rng(1))
    assert first.positions.tolist() == again.positions.tolist()
    assert first.positions[0, 0] != 30.0
