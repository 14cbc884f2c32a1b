"""The camera against the pinhole model and the contrasts lane and light detectors use.

Scenes: the built-in `straight` map (reference line along +x; east-bound lanes at
y = -1.75 and -5.25 m, 3.5 m wide; the outer edge line at y = -7 m) and the `town`.
"""

from __future__ import annotations

import io
import math

import numpy as np
import pytest
from PIL import Image

from egosim.sensors import MountPose
from egosim.sensors.camera import (
    CameraConfig,
    CameraMode,
    CameraView,
    FovAxis,
    project,
)
from egosim.sensors.camera_capture import capture
from egosim.sensors.camera_labels import SemanticClass, decode_instances, decode_semantic
from egosim.sensors.camera_scene import lamp_centres
from egosim.sensors.errors import SensorConfigError
from egosim.sensors.image_encoding import ImageFormat, encode_image
from egosim.world.signals.aspects import GREEN, RED
from egosim.world.traffic.objects import ObjectTable, ObjectType
from egosim.world.vehicle import Pose
from tests.sensors.camera_world import objects, renderer, scene_of
from tests.sensors.hsv import WHITE_HIGH, WHITE_LOW, in_band, is_red

OUTER_LANE_Y = -5.25
EDGE_LINE_Y = -7.0
CAR_POSE = Pose(x=100.0, y=OUTER_LANE_Y)
NPC_ID = 4242


def shot(
    config: CameraConfig,
    pose: Pose = CAR_POSE,
    table: ObjectTable | None = None,
    map_name: str = "straight",
    aspects: tuple[int, ...] = (),
) -> np.ndarray:
    scene = scene_of(map_name)
    if not aspects:
        aspects = (RED,) * len(scene.lights)
    return capture(
        config,
        renderer(),
        scene,
        pose,
        table if table is not None else ObjectTable.empty(),
        aspects,
    )


def pixel_of(
    point: tuple[float, float, float], config: CameraConfig, pose: Pose = CAR_POSE
) -> tuple[int, int]:
    pixels, _ = project(np.array([point]), CameraView.of(pose, config.mount), config.intrinsics())
    u, v = pixels[0]
    return round(float(u)), round(float(v))


def test_focal_length_follows_morai_vertical_fov_or_the_width() -> None:
    vertical = CameraConfig(width=640, height=480, fov_deg=90.0)
    assert vertical.focal_length_px == pytest.approx(240.0)
    horizontal = CameraConfig(width=640, height=480, fov_deg=90.0, fov_axis=FovAxis.HORIZONTAL)
    assert horizontal.focal_length_px == pytest.approx(320.0)
    k = vertical.intrinsics()
    assert (k.cx, k.cy) == (319.5, 239.5)


def test_bad_configuration_is_refused() -> None:
    with pytest.raises(SensorConfigError):
        CameraConfig(fov_deg=180.0)
    with pytest.raises(SensorConfigError):
        CameraConfig(width=0)


def test_pitch_down_moves_the_horizon_up_by_f_tan_pitch() -> None:
    config = CameraConfig(mount=MountPose(z=1.2, pitch=math.radians(10.0)))
    far_ahead = (CAR_POSE.x + 1e6, CAR_POSE.y, 1.2)
    _, v = pixel_of(far_ahead, config)
    expected = config.intrinsics().cy - config.focal_length_px * math.tan(math.radians(10.0))
    assert abs(v - expected) <= 1.0


def test_an_obstacle_box_fills_the_pixels_its_corners_project_to() -> None:
    config = CameraConfig(mode=CameraMode.INSTANCE)
    size = (2.0, 1.6, 1.4)
    foot = (CAR_POSE.x + 15.0, OUTER_LANE_Y + 0.4, 0.0)
    table = objects((NPC_ID, ObjectType.OBSTACLE, foot, 0.0, size))
    image = shot(config, table=table)
    ids = decode_instances(image)
    rows, columns = np.nonzero(ids == NPC_ID)
    corners = np.array(
        [
            (foot[0] + sx * size[0] / 2, foot[1] + sy * size[1] / 2, sz * size[2])
            for sx in (-1, 1)
            for sy in (-1, 1)
            for sz in (0, 1)
        ]
    )
    pixels, _ = project(corners, CameraView.of(CAR_POSE, config.mount), config.intrinsics())
    # A pixel is covered when its centre is inside the silhouette: the extreme covered
    # pixel centres lie within one pixel of the projected extremes.
    assert abs(columns.min() - pixels[:, 0].min()) <= 1.0
    assert abs(columns.max() - pixels[:, 0].max()) <= 1.0
    assert abs(rows.min() - pixels[:, 1].min()) <= 1.0
    assert abs(rows.max() - pixels[:, 1].max()) <= 1.0


def test_an_npc_is_vehicle_class_and_its_instance_colour_decodes_to_its_id() -> None:
    table = objects(
        (
            NPC_ID,
            ObjectType.NPC_VEHICLE,
            (CAR_POSE.x + 12.0, OUTER_LANE_Y, 0.0),
            0.0,
            (4.6, 1.9, 1.5),
        )
    )
    centre = pixel_of((CAR_POSE.x + 12.0 - 2.3, OUTER_LANE_Y, 0.4), CameraConfig())
    semantic = decode_semantic(shot(CameraConfig(mode=CameraMode.SEMANTIC), table=table))
    instance = decode_instances(shot(CameraConfig(mode=CameraMode.INSTANCE), table=table))
    u, v = centre
    assert semantic[v, u] == SemanticClass.VEHICLE
    assert instance[v, u] == NPC_ID
    # The road beside it is road, and belongs to no instance.
    road_u, road_v = pixel_of((CAR_POSE.x + 6.0, OUTER_LANE_Y, 0.0), CameraConfig())
    assert semantic[road_v, road_u] == SemanticClass.ROAD
    assert instance[road_v, road_u] == 0


def test_the_white_edge_line_passes_the_white_hsv_band_and_asphalt_and_sky_do_not() -> None:
    config = CameraConfig()
    jpeg = encode_image(shot(config), ImageFormat.JPEG, config.jpeg_quality)
    image = np.asarray(Image.open(io.BytesIO(jpeg)).convert("RGB"))
    for ahead in (6.0, 10.0, 15.0):
        u, v = pixel_of((CAR_POSE.x + ahead, EDGE_LINE_Y, 0.02), config)
        assert in_band(image[v, u], WHITE_LOW, WHITE_HIGH), (ahead, image[v, u])
        u, v = pixel_of((CAR_POSE.x + ahead, OUTER_LANE_Y, 0.0), config)
        assert not in_band(image[v, u], WHITE_LOW, WHITE_HIGH), (ahead, image[v, u])
    assert not in_band(image[20, 320], WHITE_LOW, WHITE_HIGH)


def test_the_centre_line_is_yellow_semantic_lane_marking() -> None:
    config = CameraConfig(mode=CameraMode.SEMANTIC)
    pose = Pose(x=100.0, y=-1.75)
    semantic = decode_semantic(shot(config, pose=pose))
    # The double line's two strokes are 0.15 m wide, 0.15 m apart, centred on y = 0.
    u, v = pixel_of((110.0, 0.15, 0.02), config, pose)
    assert semantic[v, u] == SemanticClass.LANE_MARKING
    rgb = shot(CameraConfig(), pose=pose)
    r, g, b = (int(c) for c in rgb[v, u])
    assert r > 200 and g > 140 and b < 80


def test_depth_of_a_flat_road_pixel_is_the_closed_form_ground_distance() -> None:
    config = CameraConfig(mode=CameraMode.DEPTH)
    depth = shot(config)
    k = config.intrinsics()
    height = config.mount.z
    for row in (300, 360, 470):
        expected = height * k.fy / (row - k.cy)
        assert depth[row, 320] == pytest.approx(expected, rel=0.01)
    assert math.isinf(depth[10, 320])


def test_a_red_lamp_is_red_in_hsv_where_the_pinhole_model_puts_it() -> None:
    scene = scene_of("town")
    site = scene.lights[0]
    facing = np.array([math.cos(site.heading), math.sin(site.heading)])
    # 25 m in front of the head, at the lamp's height, looking back at it.
    spot = np.asarray(site.position[:2]) + facing * 25.0
    pose = Pose(x=float(spot[0]), y=float(spot[1]), yaw=site.heading + math.pi)
    config = CameraConfig(mount=MountPose(z=site.position[2]))
    aspects = [RED if k == 0 else GREEN for k in range(len(scene.lights))]
    image = shot(config, pose=pose, map_name="town", aspects=tuple(aspects))
    (bit, centre), *others = lamp_centres(site)
    assert bit == RED
    u, v = pixel_of(tuple(centre), config, pose)
    assert is_red(image[v, u]), image[v, u]
    for _, other in others:
        u, v = pixel_of(tuple(other), config, pose)
        assert not is_red(image[v, u])


def test_the_same_state_gives_the_same_bytes() -> None:
    table = objects(
        (
            NPC_ID,
            ObjectType.NPC_VEHICLE,
            (CAR_POSE.x + 12.0, OUTER_LANE_Y, 0.0),
            0.3,
            (4.6, 1.9, 1.5),
        )
    )
    config = CameraConfig()
    first = encode_image(shot(config, table=table), ImageFormat.JPEG)
    second = encode_image(shot(config, table=table), ImageFormat.JPEG)
    assert first == second
