"""The broad phase of box ray casting never loses a hit that brute force finds."""

from __future__ import annotations

import numpy as np

from egosim.sensors import LidarConfig, ObstacleBoxes
from egosim.sensors.lidar import beam_directions
from egosim.sensors.raycast import Surface, cast_boxes, cast_rays
from tests.sensors.geometry import axis_rotation

MAX_RANGE = 100.0


def brute_force_distances(origin: np.ndarray, directions: np.ndarray, scene: ObstacleBoxes):
    """Every ray against every box, no culling: nearest entry distance in front of the origin."""
    nearest = np.full(len(directions), np.inf)
    for centre, size, yaw in zip(scene.centres, scene.sizes, scene.yaws, strict=True):
        to_box = axis_rotation(2, yaw).T
        local_origin = to_box @ (origin - centre)
        local_directions = directions @ to_box.T
        faces = np.stack([(-size / 2 - local_origin), (size / 2 - local_origin)])
        crossings = faces[:, None, :] / local_directions[None, :, :]
        entry = crossings.min(axis=0).max(axis=1)
        leave = crossings.max(axis=0).min(axis=1)
        hits = (entry <= leave) & (entry > 0)
        nearest[hits] = np.minimum(nearest[hits], entry[hits])
    return nearest


def cluttered_scene() -> ObstacleBoxes:
    rng = np.random.default_rng(42)
    count = 120
    centres = np.c_[rng.uniform(-130, 130, (count, 2)), rng.uniform(0.5, 2.0, count)]
    sizes = np.c_[rng.uniform(0.5, 12.0, (count, 2)), rng.uniform(0.5, 4.0, count)]
    yaws = rng.uniform(-np.pi, np.pi, count)
    special = np.array(
        [
            [-8.0, 0.0, 1.0, 3.0, 3.0, 2.0, 0.1],  # straight behind: its sector crosses +-pi
            [0.0, 0.0, 6.0, 20.0, 20.0, 2.0, 0.4],  # overhead, footprint around the sensor
            [4.0, 0.5, 1.0, 1.0, 1.0, 2.0, 0.0],  # close in front
        ]
    )
    return ObstacleBoxes(
        np.r_[centres, special[:, :3]], np.r_[sizes, special[:, 3:6]], np.r_[yaws, special[:, 6]]
    )


def test_culled_cast_matches_brute_force() -> None:
    origin = np.array([0.3, -0.2, 1.8])
    tilt = axis_rotation(1, 0.05) @ axis_rotation(0, -0.03)
    directions = beam_directions(LidarConfig(channels=32, horizontal_resolution_deg=0.5)) @ tilt.T
    scene = cluttered_scene()

    distance, _ = cast_boxes(origin, directions, scene, MAX_RANGE)
    expected = brute_force_distances(origin, directions, scene)

    in_range = expected <= MAX_RANGE
    assert in_range.sum() > 1000
    np.testing.assert_allclose(distance[in_range], expected[in_range], rtol=1e-12)
    assert np.all(distance[~in_range] > MAX_RANGE)


def test_ray_starting_inside_a_box_does_not_see_it() -> None:
    scene = ObstacleBoxes(np.array([[0.0, 0.0, 1.0]]), np.array([[4.0, 2.0, 2.0]]), np.zeros(1))
    directions = beam_directions(LidarConfig(channels=4, horizontal_resolution_deg=10.0))
    distance, _ = cast_boxes(np.array([0.0, 0.0, 1.0]), directions, scene, MAX_RANGE)
    assert np.all(np.isinf(distance))


def test_incidence_and_surface_of_hits() -> None:
    scene = ObstacleBoxes(np.array([[10.0, 0.0, 1.0]]), np.array([[2.0, 2.0, 2.0]]), np.zeros(1))
    down = np.array([0.0, -np.sin(0.5), -np.cos(0.5)])
    ahead = np.array([1.0, 0.0, 0.0])
    up = np.array([0.0, 0.0, 1.0])
    hits = cast_rays(np.array([0.0, 0.0, 1.0]), np.stack([down, ahead, up]), scene, MAX_RANGE)
    np.testing.assert_array_equal(hits.surface, [Surface.GROUND, Surface.OBJECT, Surface.NONE])
    np.testing.assert_allclose(hits.distance[:2], (1.0 / np.cos(0.5), 9.0))
    np.testing.assert_allclose(hits.cos_incidence, (np.cos(0.5), 1.0, 0.0))
