"""LiDAR scans against known geometry: boxes, ground and the sensor frame."""

from __future__ import annotations

import numpy as np
import pytest

from egosim.sensors import LidarConfig, LidarIntensity, LidarModel, MountPose, ObstacleBoxes, Pose
from egosim.sensors.errors import SensorConfigError

FLOAT32_TOLERANCE = 1e-5  # relative


def boxes(*specs: tuple[tuple[float, float, float], tuple[float, float, float], float]):
    centres, sizes, yaws = zip(*specs, strict=True)
    return ObstacleBoxes(np.array(centres), np.array(sizes), np.array(yaws))


def horizontal_ring(**overrides) -> LidarModel:
    """One level channel every degree; the sensor 1 m above base_link."""
    settings = dict(
        channels=1,
        min_elevation_deg=0.0,
        max_elevation_deg=0.0,
        horizontal_resolution_deg=1.0,
        mount=MountPose(z=1.0),
    )
    return LidarModel(LidarConfig(**(settings | overrides)))


def point_at_azimuth(points: np.ndarray, azimuth_rad: float) -> np.ndarray:
    bearings = np.arctan2(points[:, 1], points[:, 0])
    matches = points[np.isclose(bearings, azimuth_rad, atol=1e-4)]
    assert len(matches) == 1
    return matches[0]


def test_beam_returns_distance_to_box_face() -> None:
    points = horizontal_ring().scan(Pose(), boxes(((20.0, 0.0, 1.0), (2.0, 2.0, 2.0), 0.0)))
    ahead = point_at_azimuth(points, 0.0)
    np.testing.assert_allclose(ahead[:3], (19.0, 0.0, 0.0), rtol=FLOAT32_TOLERANCE, atol=1e-6)
    # Every return lies on the front face plane x = 19 at range 19 / cos(azimuth).
    np.testing.assert_allclose(points[:, 0], 19.0, rtol=FLOAT32_TOLERANCE)
    assert np.all(np.abs(points[:, 1]) <= 1.0 + 1e-5)
    assert np.all(points[:, 3] > 0.0)


def test_beam_meets_the_corner_of_a_turned_box() -> None:
    model = horizontal_ring()
    points = model.scan(Pose(), boxes(((20.0, 0.0, 1.0), (2.0, 2.0, 2.0), np.pi / 4)))
    ahead = point_at_azimuth(points, 0.0)
    assert ahead[0] == pytest.approx(20.0 - np.sqrt(2.0), rel=FLOAT32_TOLERANCE)


def test_nearest_of_two_boxes_in_line_is_returned() -> None:
    scene = boxes(
        ((40.0, 0.0, 1.0), (2.0, 4.0, 2.0), 0.0), ((10.0, 0.0, 1.0), (1.0, 1.0, 2.0), 0.0)
    )
    ahead = point_at_azimuth(horizontal_ring().scan(Pose(), scene), 0.0)
    assert ahead[0] == pytest.approx(9.5, rel=FLOAT32_TOLERANCE)


def test_boxes_below_the_ground_horizon_are_not_hit() -> None:
    model = LidarModel(
        LidarConfig(
            channels=5, min_elevation_deg=-10.0, max_elevation_deg=-2.0, mount=MountPose(z=2.0)
        )
    )
    ground_only = model.scan(Pose())
    # The shallowest beam reaches the ground 2 / tan(2 deg) = 57 m out; beyond it a low box hides.
    far_low_box = ((80.0, 0.0, 0.5), (4.0, 2.0, 1.0), 0.0)
    buried_box = ((10.0, 0.0, -2.0), (4.0, 4.0, 2.0), 0.0)
    np.testing.assert_array_equal(model.scan(Pose(), boxes(far_low_box, buried_box)), ground_only)
    near_box = ((30.0, 0.0, 0.5), (4.0, 2.0, 1.0), 0.0)
    assert not np.array_equal(model.scan(Pose(), boxes(near_box)), ground_only)


def test_point_count_is_beams_minus_misses() -> None:
    config = LidarConfig()
    height = config.mount.z
    elevations = np.radians(-15.0 + 2.0 * np.arange(16))
    # Over flat empty ground a downward beam returns at height / sin(-elevation) if in range.
    ground_range = height / np.sin(-elevations[elevations < 0])
    returning_channels = np.count_nonzero(
        (ground_range >= config.min_range_m) & (ground_range <= config.max_range_m)
    )
    points = LidarModel(config).scan(Pose())
    horizontal_steps = 1800
    misses = 16 * horizontal_steps - returning_channels * horizontal_steps
    assert len(points) == 16 * horizontal_steps - misses
    np.testing.assert_allclose(points[:, 2], -height, rtol=FLOAT32_TOLERANCE)


def test_nothing_in_range_gives_an_empty_cloud() -> None:
    model = LidarModel(LidarConfig(max_range_m=1.0))
    points = model.scan(Pose(), boxes(((30.0, 0.0, 1.0), (2.0, 2.0, 2.0), 0.0)))
    assert points.shape == (0, 4)
    assert points.dtype == np.float32


def test_hits_closer_than_min_range_give_no_point() -> None:
    scene = boxes(((1.0, 0.0, 1.0), (1.0, 1.0, 2.0), 0.0))
    points = horizontal_ring(min_range_m=0.6).scan(Pose(), scene)
    assert np.all(np.hypot(points[:, 0], points[:, 1]) >= 0.6)
    assert len(points) < 360


def test_own_box_is_excluded() -> None:
    model = LidarModel()
    ego = ((0.0, 0.0, 0.75), (4.5, 1.9, 1.5), 0.0)
    other = ((15.0, 3.0, 0.75), (4.5, 1.9, 1.5), 0.3)
    scene_with_ego = boxes(other, ego)
    # The roof is 0.3 m under the sensor, so it would shadow the near ground.
    assert not np.array_equal(model.scan(Pose(), scene_with_ego), model.scan(Pose(), boxes(other)))
    np.testing.assert_array_equal(
        model.scan(Pose(), scene_with_ego, exclude_index=1), model.scan(Pose(), boxes(other))
    )


def test_points_are_in_the_sensor_frame() -> None:
    # Facing north with a 2 m cube centred 20 m ahead: its near face is 19 m ahead of base_link.
    vehicle = Pose(x=100.0, y=30.0, yaw=np.pi / 2)
    scene = boxes(((100.0, 50.0, 1.0), (2.0, 2.0, 2.0), 0.0))
    for mount_x in (0.0, 1.5):
        model = horizontal_ring(mount=MountPose(x=mount_x, z=1.0))
        ahead = point_at_azimuth(model.scan(vehicle, scene), 0.0)
        np.testing.assert_allclose(ahead[:3], (19.0 - mount_x, 0.0, 0.0), rtol=1e-5, atol=1e-5)
    # Turned a quarter turn left, the sensor sees what is ahead of the car on its right (-y).
    turned = horizontal_ring(mount=MountPose(z=1.0, yaw=np.pi / 2)).scan(vehicle, scene)
    np.testing.assert_allclose(
        point_at_azimuth(turned, -np.pi / 2)[:3], (0.0, -19.0, 0.0), rtol=1e-5, atol=1e-5
    )
    # Pitched down, the cube's face is seen below the sensor's horizon at the same range.
    pitch = np.radians(2.0)
    pitched = horizontal_ring(mount=MountPose(z=1.0, pitch=pitch)).scan(vehicle, scene)
    ahead = point_at_azimuth(pitched, 0.0)
    assert ahead[0] == pytest.approx(19.0 / np.cos(pitch), rel=FLOAT32_TOLERANCE)


def test_scans_are_deterministic() -> None:
    rng = np.random.default_rng(2)
    scene = ObstacleBoxes(
        np.c_[rng.uniform(-60, 60, (50, 2)), np.full(50, 0.8)],
        np.tile((4.5, 1.9, 1.6), (50, 1)),
        rng.uniform(-np.pi, np.pi, 50),
    )
    model = LidarModel()
    assert model.scan(Pose(), scene).tobytes() == model.scan(Pose(), scene).tobytes()


@pytest.mark.parametrize(
    "settings",
    [
        {"channels": 0},
        {"min_elevation_deg": 10.0, "max_elevation_deg": -10.0},
        {"horizontal_resolution_deg": 0.7},
        {"min_range_m": 5.0, "max_range_m": 1.0},
        {"rate_hz": 0.0},
    ],
)
def test_invalid_configurations_are_refused(settings: dict) -> None:
    with pytest.raises(SensorConfigError):
        LidarConfig(**settings)


def test_intensity_follows_reflectivity_incidence_and_range() -> None:
    intensity = LidarIntensity(
        ground_reflectivity=0.2, object_reflectivity=0.6, extinction_per_m=0.005
    )
    scene = boxes(((20.0, 0.0, 1.0), (2.0, 2.0, 2.0), 0.0))
    ahead = point_at_azimuth(horizontal_ring(intensity=intensity).scan(Pose(), scene), 0.0)
    assert ahead[3] == pytest.approx(255.0 * 0.6 * np.exp(-2 * 0.005 * 19.0), rel=1e-5)
    # The steepest beam meets the ground 15 deg from grazing, height / sin(15 deg) away.
    config = LidarConfig(intensity=intensity)
    steepest = LidarModel(config).scan(Pose())[0]
    ground_range = config.mount.z / np.sin(np.radians(15.0))
    assert np.linalg.norm(steepest[:3]) == pytest.approx(ground_range, rel=1e-5)
    expected = 255.0 * 0.2 * np.sin(np.radians(15.0)) * np.exp(-2 * 0.005 * ground_range)
    assert steepest[3] == pytest.approx(expected, rel=1e-5)
