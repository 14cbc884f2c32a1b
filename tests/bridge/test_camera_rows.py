"""Camera and radar rows over a real world: settings, messages, sync capture, files."""

from __future__ import annotations

import io
import logging
import math
from pathlib import Path
from types import SimpleNamespace
from typing import Any

import numpy as np
import pytest
from PIL import Image

from egosim.bridge import ClockMode, simulation_context
from egosim.bridge.context import BridgeContext
from egosim.bridge.protocol.network import parse_network_settings
from egosim.bridge.sensors import camera_rig, camera_rows, sensor_files, sensor_rows
from egosim.bridge.sensors.camera_rig import open_camera_rig
from egosim.bridge.sensors.sensor_rig import SensorRig
from egosim.msgs import get_profile
from egosim.sensors import RendererUnavailableError
from egosim.sensors.camera_render import RenderRequest
from egosim.sensors.camera_scene import StaticScene
from egosim.world import World
from egosim.world.map import build_builtin_map
from egosim.world.vehicle import DEFAULT_EGO_MODEL, sensor_mount_origin, vehicle_model
from egosim.yamltext import YamlFileError
from tests.bridge.built_rows import built
from tests.sensors.camera_world import renderer

PROFILE = get_profile("26.r1")
TWO_CAMERAS_AND_DEPTH = """
sensors:
  cameras:
    - {}
    - {mode: semantic, width: 320, height: 240, mount: {yaw_deg: 180}}
    - {mode: depth, width: 160, height: 120}
"""


def context_for(text: str | None = None, sync: bool = False, roots=()) -> BridgeContext:
    settings = parse_network_settings(text or "", "net.yaml")
    world = World(build_builtin_map("straight"))
    return simulation_context(
        world,
        settings=settings,
        clock_mode=ClockMode.SYNC if sync else ClockMode.SIM,
        data_roots=roots,
        open_renderer=renderer,
    )


def test_camera_info_sits_beside_its_image_topic() -> None:
    assert camera_rows.camera_info_topic("/image_jpeg/compressed") == "/image_jpeg/camera_info"
    assert camera_rows.camera_info_topic("/image") == "/camera_info"
    assert camera_rows.camera_info_topic("/front/image_raw") == "/front/camera_info"


def test_cameras_sharing_a_topic_are_numbered_and_depth_goes_to_image() -> None:
    rig = SensorRig(parse_network_settings(TWO_CAMERAS_AND_DEPTH, "n").sensors, None)  # type: ignore[arg-type]
    assert rig.camera_topics == ("/image_jpeg/compressed", "/image_jpeg/compressed", "/image")
    assert rig.camera_frame_ids == ("Camera-1", "Camera-2", "Camera")
    # SensorPosControl: 0 GPS, 1 IMU, 2 LiDAR, 3.. the cameras, then the radar.
    assert rig.radar_index == 6


@pytest.mark.parametrize(
    ("text", "field"),
    [
        ("sensors:\n  cameras:\n    - {mode: thermal}\n", "sensors.cameras.0.mode"),
        ("sensors:\n  cameras:\n    - {fov_deg: 200}\n", "sensors.cameras.0"),
        ("sensors:\n  cameras:\n    - {mode: depth, format: png}\n", "sensors.cameras.0.format"),
        ("sensors:\n  cameras:\n    - {topic: image}\n", "sensors.cameras.0.topic"),
        ("sensors:\n  cameras: {width: 3}\n", "sensors.cameras"),
        ("sensors:\n  radar: {max_detections: -1}\n", "sensors.radar"),
    ],
)
def test_bad_camera_settings_name_the_field(text: str, field: str) -> None:
    with pytest.raises(YamlFileError) as raised:
        parse_network_settings(text, "net.yaml")
    assert field in str(raised.value)


def test_the_front_camera_sends_a_jpeg_and_its_camera_info() -> None:
    context = context_for()
    image = camera_rows.camera_image_message(context, 0)
    assert (image.format, image.header.frame_id) == ("jpeg", "Camera")
    decoded = Image.open(io.BytesIO(bytes(image.data)))
    assert (decoded.format, decoded.size) == ("JPEG", (640, 480))
    info = camera_rows.camera_info_message(context, 0)
    assert info.header.frame_id == "Camera_optical"
    assert (info.width, info.height, info.distortion_model) == (640, 480, "plumb_bob")
    assert info.K.tolist() == pytest.approx([240.0, 0.0, 319.5, 0.0, 240.0, 239.5, 0.0, 0.0, 1.0])
    assert info.P.tolist()[:4] == pytest.approx([240.0, 0.0, 319.5, 0.0])
    serialized = PROFILE.message("sensor_msgs/CameraInfo").serialize(info)
    assert PROFILE.message("sensor_msgs/CameraInfo").deserialize(serialized).K[2] == 319.5


def test_labels_are_png_and_depth_is_32fc1_metres() -> None:
    context = context_for(TWO_CAMERAS_AND_DEPTH)
    semantic = camera_rows.camera_image_message(context, 1)
    assert semantic.format == "png"
    assert Image.open(io.BytesIO(bytes(semantic.data))).size == (320, 240)
    depth = camera_rows.camera_image_message(context, 2)
    assert (depth.encoding, depth.width, depth.height, depth.step) == ("32FC1", 160, 120, 640)
    metres = np.frombuffer(bytes(depth.data), dtype="<f4").reshape(120, 160)
    height = 1.2 + sensor_mount_origin(vehicle_model(DEFAULT_EGO_MODEL))[2]
    focal = 60.0  # 120 px, 90 deg vertical
    row = 100
    assert metres[row, 80] == pytest.approx(height * focal / (row - 59.5), rel=0.01)


def test_in_sync_mode_cameras_render_only_for_a_captured_frame() -> None:
    # --clock sync: the world waits for a client, so time is held from the start.
    context = context_for(sync=True)
    row = context.row("camera")
    build = camera_rows._image_builder((0,), camera_rows.CameraSchedule(30.0))
    assert build(context, row) is None
    context.sync.capture_cameras = True
    context.pipeline.loop_time += 0.01
    assert len(build(context, row)) == 1


def test_outside_sync_mode_cameras_publish_at_their_rate() -> None:
    context = context_for()
    row = context.row("camera")
    build = camera_rows._info_builder((0,), camera_rows.CameraSchedule(10.0))
    published = []
    for tick in range(1, 51):  # 0.5 s of 10 ms ticks
        context.pipeline.loop_time = tick * 0.01
        if build(context, row) is not None:
            published.append(tick)
    # At once, then every 10 ticks (0.1 s).
    assert published == [1, 11, 21, 31, 41]


def test_sensor_pos_control_moves_a_camera_and_its_tf() -> None:
    context = context_for()
    command = PROFILE.message("morai_msgs/SensorPosControl").new(
        sensor_index=np.array([3], dtype=np.int16),
        **{
            name: np.array([value], dtype=np.float32)
            for name, value in zip(
                ("pose_x", "pose_y", "pose_z", "roll", "pitch", "yaw"),
                (2.0, 0.5, 1.0, 0.0, 0.0, 0.0),
                strict=True,
            )
        },
    )
    sensor_rows.on_sensor_pos_control(context, context.row("sensor_pos_control"), command)
    tf = built(context, "tf")
    transforms = {t.child_frame_id: t.transform for t in tf.transforms}
    x, _, z = sensor_mount_origin(vehicle_model(DEFAULT_EGO_MODEL))
    camera = transforms["Camera"].translation
    assert (camera.x, camera.y, camera.z) == pytest.approx((2.0 + x, 0.5, 1.0 + z))
    optical = transforms["Camera_optical"].rotation
    # z forward, x right, y down: the quaternion of that rotation.
    assert (optical.x, optical.y, optical.z, optical.w) == pytest.approx((-0.5, 0.5, -0.5, 0.5))


def test_save_sensor_data_writes_each_camera_frame(tmp_path: Path) -> None:
    context = context_for(TWO_CAMERAS_AND_DEPTH, roots=[tmp_path])
    request = SimpleNamespace(
        file_dir=str(tmp_path), is_custom_file_name=True, custom_file_name="f"
    )
    sensor_files.on_save_sensor_data(context, context.row("save_sensor_data"), request)
    names = sorted(p.name for p in tmp_path.iterdir())
    assert names == ["f.json", "f.pcd", "f_Camera-1.jpg", "f_Camera-2.png", "f_Camera.tiff"]
    depth = np.asarray(Image.open(tmp_path / "f_Camera.tiff"))
    assert depth.dtype == np.float32 and depth.shape == (120, 160)


class WatchedRenderer:
    """The real renderer, noting each scene it is asked to load and each it draws."""

    def __init__(self, inner: Any) -> None:
        self.inner = inner
        self.loaded: list[StaticScene] = []
        self.drawn: list[StaticScene] = []

    def load(self, scene: StaticScene) -> None:
        self.loaded.append(scene)
        self.inner.load(scene)

    def render(self, request: RenderRequest) -> Any:
        self.drawn.append(request.scene)
        return self.inner.render(request)


def test_the_map_scene_is_built_and_loaded_with_the_rig_not_in_a_frame() -> None:
    watched = WatchedRenderer(renderer())
    world = World(build_builtin_map("straight"))
    context = simulation_context(world, open_renderer=lambda: watched)
    assert context.cameras is not None
    scene = context.cameras.scene
    assert watched.loaded == [scene] and watched.drawn == []
    for _ in range(3):
        camera_rows.camera_image_message(context, 0)
    assert watched.loaded == [scene] and watched.drawn == [scene] * 3
    # The next simulator on the same map (a batch worker's next case) reuses the scene.
    again = simulation_context(World(world.map), open_renderer=lambda: watched)
    assert again.cameras is not None and again.cameras.scene is scene


def test_asked_to_the_scene_is_built_when_the_first_frame_is_taken(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    built: list[StaticScene] = []
    build = camera_rig.static_scene

    def counted(lane_map: Any) -> StaticScene:
        built.append(build(lane_map))
        return built[-1]

    monkeypatch.setattr(camera_rig, "static_scene", counted)
    watched = WatchedRenderer(renderer())
    world = World(build_builtin_map("straight"))
    context = simulation_context(
        world, open_renderer=lambda: watched, camera_scene_at_first_frame=True
    )
    assert context.cameras is not None
    assert built == [] and watched.loaded == []  # a batch case that takes no frame
    first = camera_rows.camera_image_message(context, 0)
    assert watched.loaded == built == [context.cameras.scene]
    camera_rows.camera_image_message(context, 0)
    assert len(built) == 1 and watched.drawn == built * 2
    # The same frame as a scene built at the start gives.
    eager = simulation_context(World(world.map), open_renderer=lambda: watched)
    assert bytes(camera_rows.camera_image_message(eager, 0).data) == bytes(first.data)


def test_without_a_renderer_the_cameras_are_off_in_one_line(caplog) -> None:
    settings = parse_network_settings("", "net.yaml")
    world = World(build_builtin_map("straight"))

    def unavailable() -> None:
        raise RendererUnavailableError("no EGL here")

    with caplog.at_level(logging.WARNING):
        rig = SensorRig(settings.sensors, world.map.georef)
        assert open_camera_rig(rig, unavailable, world.map) is None
    assert [r.getMessage() for r in caplog.records] == ["cameras off: no EGL here"]


def test_radar_message_reports_degrees_and_the_object_id() -> None:
    text = "sensors:\n  radar: {horizontal_fov_deg: 360}\n"
    context = context_for(text)
    world = context.world
    world.add_object("Box", (30.0, 5.0, 0.0), 0.0)
    message = sensor_rows.publish_radar(context, context.row("radar"))
    assert message.header.frame_id == "radar"
    assert len(message.detections) == 1
    detection = message.detections[0]
    assert 0.0 < detection.azimuth < 90.0
    position = detection.position
    assert math.degrees(math.atan2(position.y, position.x)) == pytest.approx(
        detection.azimuth, abs=1e-3
    )
