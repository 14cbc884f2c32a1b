"""What a camera skips: tiles, objects and lights out of view, and far detail. Culling
never drops what the pinhole model puts in the image, far tiles are drawn coarse, and
the image stays as drawing everything gives it."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from egosim.sensors.camera import CameraConfig, CameraView, project, scene_matrices
from egosim.sensors.camera_capture import capture
from egosim.sensors.camera_frame_mesh import build_frame_mesh
from egosim.sensors.camera_render import RenderRequest
from egosim.sensors.camera_scene import StaticScene
from egosim.sensors.scene_tiles import SceneTiles, coarse_beyond_m, visible_ranges
from egosim.world import World
from egosim.world.map import build_builtin_map
from egosim.world.scenario import load_default_scenario
from egosim.world.signals.aspects import RED
from egosim.world.traffic.objects import ObjectTable
from egosim.world.vehicle import Pose
from tests.sensors.camera_world import renderer, scene_of

CONFIG = CameraConfig()


def town_poses() -> list[Pose]:
    """Driver's poses on every 60th lane of the town, 5 m along it."""
    lane_map = build_builtin_map("town")
    poses = []
    for lane_id in sorted(lane_map.lanes)[::60]:
        x, y, z, heading = lane_map.pose_at(lane_id, 5.0)
        poses.append(Pose(x=x, y=y, z=z, yaw=heading))
    return poses


def fine_vertex_count(scene: StaticScene) -> int:
    return int(scene.tiles.count[:, 0].sum())


def drawn(ranges: list[tuple[int, int]], size: int) -> np.ndarray:
    mask = np.zeros(size, dtype=bool)
    for first, count in ranges:
        mask[first : first + count] = True
    return mask


def ranges_for(scene: StaticScene, pose: Pose, focal_px: float) -> list[tuple[int, int]]:
    view = CameraView.of(pose, CONFIG.mount)
    _, clip = scene_matrices(view, CONFIG.intrinsics(), CONFIG.near_m, CONFIG.far_m, scene.origin)
    return visible_ranges(scene.tiles, clip, view.origin - scene.origin, focal_px)


def test_every_triangle_the_pinhole_model_puts_in_the_image_is_drawn() -> None:
    scene = scene_of("town")
    fine = fine_vertex_count(scene)
    points = scene.mesh.positions[:fine].astype(np.float64) + scene.origin
    intrinsics = CONFIG.intrinsics()
    shares = []
    for pose in town_poses():
        shown = drawn(ranges_for(scene, pose, math.inf), len(scene.mesh))
        assert not shown[fine:].any(), "a camera with no far range drew coarse tiles"
        pixels, depth = project(points, CameraView.of(pose, CONFIG.mount), intrinsics)
        with np.errstate(invalid="ignore"):
            in_image = (
                (depth > CONFIG.near_m)
                & (depth < CONFIG.far_m)
                & (pixels[:, 0] >= -0.5)
                & (pixels[:, 0] <= intrinsics.width - 0.5)
                & (pixels[:, 1] >= -0.5)
                & (pixels[:, 1] <= intrinsics.height - 0.5)
            )
        seen = in_image.reshape(-1, 3).any(axis=1)
        kept = shown[:fine].reshape(-1, 3)[:, 0]
        assert kept[seen].all(), f"{(seen & ~kept).sum()} triangles in view culled at {pose}"
        shares.append(kept.mean())
    assert np.mean(shares) < 0.5, f"culling drew {np.mean(shares):.0%} of the town on average"


def test_tiles_beyond_the_coarse_distance_are_drawn_coarse_and_cheaper() -> None:
    scene = scene_of("town")
    fine = fine_vertex_count(scene)
    focal = CONFIG.intrinsics().fy
    beyond = coarse_beyond_m(focal)
    assert beyond == focal * 0.25 / 0.5
    for pose in town_poses():
        eye = CameraView.of(pose, CONFIG.mount).origin - scene.origin
        all_fine = drawn(ranges_for(scene, pose, math.inf), len(scene.mesh))
        shown = drawn(ranges_for(scene, pose, focal), len(scene.mesh))
        coarse_points = scene.mesh.positions[fine:][shown[fine:]].astype(np.float64)
        assert np.all(np.linalg.norm(coarse_points - eye, axis=1) > beyond)
        assert shown.sum() < all_fine.sum()


def whole(scene: StaticScene) -> StaticScene:
    """The scene as one tile: every triangle drawn, at the fine level."""
    fine = fine_vertex_count(scene)
    return replace(
        scene,
        tiles=SceneTiles(
            first=np.zeros((1, 2), np.int64),
            count=np.full((1, 2), fine, np.int64),
            lower=np.full((1, 3), -1e6),
            upper=np.full((1, 3), 1e6),
        ),
    )


def shoot(scene: StaticScene, pose: Pose) -> np.ndarray:
    aspects = (RED,) * len(scene.lights)
    return capture(CONFIG, renderer(), scene, pose, ObjectTable.empty(), aspects)


def test_culling_leaves_the_image_as_the_whole_scene_draws_it() -> None:
    scene = scene_of("town")
    tiles = scene.tiles
    fine_only = replace(
        scene, tiles=replace(tiles, first=tiles.first[:, [0, 0]], count=tiles.count[:, [0, 0]])
    )
    everything = whole(scene)
    for pose in town_poses():
        assert np.array_equal(shoot(fine_only, pose), shoot(everything, pose)), pose


def test_far_tiles_drawn_coarse_change_almost_no_pixel() -> None:
    scene = scene_of("town")
    everything = whole(scene)
    for pose in town_poses():
        changed = np.any(shoot(scene, pose) != shoot(everything, pose), axis=2)
        # Far edges move less than half a pixel: only pixels whose centres lay that
        # close to one may change (0-3 of 307 200 in these views).
        assert changed.mean() < 1e-4, f"{changed.sum()} pixels changed at {pose}"


def test_objects_and_lights_out_of_view_are_left_out_and_the_image_is_unchanged() -> None:
    world = World(build_builtin_map("town"), load_default_scenario())
    for _ in range(200):
        world.step()
    scene = scene_of("town")
    pose = world.ego_status(0).pose
    view = CameraView.of(pose, CONFIG.mount)
    intrinsics = CONFIG.intrinsics()
    _, clip = scene_matrices(view, intrinsics, CONFIG.near_m, CONFIG.far_m, scene.origin)
    objects, aspects = world.objects(), world.signals.aspects()
    hidden = (world.egos[0].unique_id,)
    every = build_frame_mesh(scene, objects, aspects, hidden)
    in_view = build_frame_mesh(scene, objects, aspects, hidden, clip)
    assert 0 < len(in_view) < len(every) / 2
    images = [
        renderer().render(
            RenderRequest(scene, frame, view, intrinsics, CONFIG.mode, CONFIG.near_m, CONFIG.far_m)
        )
        for frame in (every, in_view)
    ]
    assert np.array_equal(*images)
