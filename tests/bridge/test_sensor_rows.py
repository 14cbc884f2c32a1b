"""The sensor rows over a real world: what /lidar3D, /imu, /tf and SaveSensorData carry."""

from __future__ import annotations

import json
import math
from dataclasses import replace
from pathlib import Path
from types import SimpleNamespace
from typing import Any

import numpy as np
import pytest

from egosim.bridge import HANDLERS, default_network_settings, simulation_context
from egosim.bridge.context import BridgeContext
from egosim.bridge.protocol.sensor_settings import LidarSettings, SensorSettings
from egosim.bridge.sensors import sensor_files, sensor_rows
from egosim.bridge.sensors.sensor_rig import LIDAR_INDEX
from egosim.msgs import get_profile
from egosim.sensors import LidarConfig
from egosim.world import World
from egosim.world.map import build_builtin_map
from egosim.world.scenario import parse_scenario
from egosim.world.vehicle import DEFAULT_EGO_MODEL, sensor_mount_origin, vehicle_model
from tests.bridge.built_rows import built

PROFILE = get_profile("26.r1")
# Mounts are MORAI's: from the rear-axle midpoint at wheel-centre height.
MOUNT_ORIGIN = sensor_mount_origin(vehicle_model(DEFAULT_EGO_MODEL))
LIDAR_HEIGHT_M = 1.8 + MOUNT_ORIGIN[2]
# The ego starts at x = 0 heading east on the straight map's first lane (y = -1.75).
BOX_NEAR_FACE_X_M = 20.0
BOX_SCENARIO = f"""
map: straight
ego: {{model: 2016_Kia_Niro(HEV), start: {{lane: R1_E_1, s: 0.0}}}}
obstacles:
  - model: Box
    pose: {{x: {BOX_NEAR_FACE_X_M + 0.5}, y: -1.75}}
    size: {{length: 1.0, width: 4.0, height: 3.0}}
"""


def context_for(world: World, lidar: LidarConfig | None = None, roots=()) -> BridgeContext:
    sensors = SensorSettings(lidar=LidarSettings(config=lidar or LidarConfig()))
    settings = replace(default_network_settings(), sensors=sensors)
    return simulation_context(world, settings=settings, data_roots=roots)


def published(key: str, context: BridgeContext) -> Any:
    """What the publishing row `key` sends now."""
    return HANDLERS.publishers[key](context, context.row(key))


def save_sensor_data(context: BridgeContext, request: Any) -> None:
    """/SaveSensorData receives `request`."""
    sensor_files.on_save_sensor_data(context, context.row("save_sensor_data"), request)


def empty_world() -> World:
    return World(build_builtin_map("straight"))


def cloud_points(message) -> np.ndarray:
    """The (M, 4) float32 points of a PointCloud2 after a trip through its bytes."""
    cloud_type = PROFILE.message("sensor_msgs/PointCloud2")
    decoded = cloud_type.deserialize(cloud_type.serialize(message))
    assert [f.name for f in decoded.fields] == ["x", "y", "z", "intensity"]
    assert decoded.point_step == 16
    return np.frombuffer(bytes(decoded.data), dtype="<f4").reshape(-1, 4)


def test_point_count_is_beams_minus_misses_on_open_ground() -> None:
    config = LidarConfig()
    points = cloud_points(published("lidar", context_for(empty_world(), config)))
    # Only beams below the horizon that meet the ground within range return a point.
    elevations = config.elevations_rad
    ground_range = np.where(elevations < 0, LIDAR_HEIGHT_M / np.sin(-elevations), np.inf)
    returning = (ground_range >= config.min_range_m) & (ground_range <= config.max_range_m)
    misses = config.horizontal_steps * int(np.count_nonzero(~returning))
    assert len(points) == config.channels * config.horizontal_steps - misses
    assert np.allclose(points[:, 2], -LIDAR_HEIGHT_M, atol=1e-4)  # all on the ground


def test_a_beam_at_a_box_returns_its_distance() -> None:
    world = World(build_builtin_map("straight"), parse_scenario(BOX_SCENARIO, "box.yaml"))
    # 31 channels over -15..15 deg: channel 15 is level; 360 steps: step 0 looks ahead.
    config = LidarConfig(channels=31, horizontal_resolution_deg=1.0)
    points = cloud_points(published("lidar", context_for(world, config)))
    level_ahead = points[(np.abs(points[:, 2]) < 1e-4) & (np.abs(points[:, 1]) < 1e-4)]
    assert len(level_ahead) == 1
    # The LiDAR stands on the mount origin, MOUNT_ORIGIN[0] ahead of base_link.
    assert level_ahead[0, 0] == pytest.approx(BOX_NEAR_FACE_X_M - MOUNT_ORIGIN[0], abs=1e-4)
    assert level_ahead[0, 3] > 0.0


def test_imu_at_rest_reads_gravity_up_and_no_rotation() -> None:
    imu = published("imu", context_for(empty_world()))
    acceleration, rate = imu.linear_acceleration, imu.angular_velocity
    assert (acceleration.x, acceleration.y) == pytest.approx((0.0, 0.0), abs=1e-9)
    assert acceleration.z == pytest.approx(9.81, abs=0.01)
    assert (rate.x, rate.y, rate.z) == pytest.approx((0.0, 0.0, 0.0), abs=1e-12)


def test_tf_places_base_link_at_the_ego_and_sensors_at_their_mounts() -> None:
    world = empty_world()
    context = context_for(world)
    message = built(context, "tf")
    frames = {(t.header.frame_id, t.child_frame_id): t.transform for t in message.transforms}
    assert set(frames) == {
        ("map", "base_link"),
        *(("base_link", f) for f in ("gps", "imu", "lidar", "Camera", "radar")),
        ("Camera", "Camera_optical"),
    }
    pose = world.ego_status().pose
    base = frames[("map", "base_link")].translation
    assert (base.x, base.y, base.z) == pytest.approx((pose.x, pose.y, pose.z))
    lidar = frames[("base_link", "lidar")].translation
    assert (lidar.x, lidar.z) == pytest.approx((MOUNT_ORIGIN[0], LIDAR_HEIGHT_M))


def sensor_pos_control(**arrays):
    return PROFILE.message("morai_msgs/SensorPosControl").new(
        sensor_index=np.array(arrays.pop("sensor_index"), dtype=np.int16),
        **{name: np.array(values, dtype=np.float32) for name, values in arrays.items()},
    )


def test_sensor_pos_control_moves_the_lidar_and_its_ground_ring() -> None:
    context = context_for(
        empty_world(), LidarConfig(channels=1, min_elevation_deg=-30.0, max_elevation_deg=-30.0)
    )
    command = sensor_pos_control(
        sensor_index=[LIDAR_INDEX],
        pose_x=[1.0],
        pose_y=[0.0],
        pose_z=[1.0],
        roll=[0.0],
        pitch=[0.0],
        yaw=[math.pi / 2],
    )
    sensor_rows.on_sensor_pos_control(context, context.row("sensor_pos_control"), command)
    transforms = built(context, "tf").transforms
    lidar = next(t.transform for t in transforms if t.child_frame_id == "lidar")
    x, _, z = MOUNT_ORIGIN
    assert (lidar.translation.x, lidar.translation.z) == pytest.approx((1.0 + x, 1.0 + z))
    assert (lidar.rotation.z, lidar.rotation.w) == pytest.approx((math.sqrt(0.5), math.sqrt(0.5)))
    points = cloud_points(sensor_rows.publish_lidar(context, context.row("lidar")))
    # At h = 1 m + the origin's height a -30 deg beam meets the ground 2 h along the beam.
    assert np.linalg.norm(points[:, :3], axis=1) == pytest.approx(
        np.full(len(points), 2.0 * (1.0 + z)), abs=1e-4
    )


def test_sensor_pos_control_ignores_bad_entries(caplog) -> None:
    context = context_for(empty_world())
    before = context.sensors.mounts()
    ragged = sensor_pos_control(
        sensor_index=[0, 1],
        pose_x=[1.0],
        pose_y=[0.0],
        pose_z=[0.0],
        roll=[0.0],
        pitch=[0.0],
        yaw=[0.0],
    )
    unknown = sensor_pos_control(
        sensor_index=[7],
        pose_x=[1.0],
        pose_y=[0.0],
        pose_z=[0.0],
        roll=[0.0],
        pitch=[0.0],
        yaw=[0.0],
    )
    not_finite = sensor_pos_control(
        sensor_index=[0],
        pose_x=[math.nan],
        pose_y=[0.0],
        pose_z=[0.0],
        roll=[0.0],
        pitch=[0.0],
        yaw=[0.0],
    )
    for message in (ragged, unknown, not_finite):
        sensor_rows.on_sensor_pos_control(context, context.row("sensor_pos_control"), message)
    assert context.sensors.mounts() == before
    assert "differ in length" in caplog.text
    assert "no sensor 7" in caplog.text
    assert "not finite" in caplog.text


def save_request(file_dir: str, name: str = ""):
    return SimpleNamespace(is_custom_file_name=bool(name), custom_file_name=name, file_dir=file_dir)


def test_save_sensor_data_writes_the_cloud_and_the_readings(tmp_path: Path) -> None:
    (tmp_path / "out").mkdir()
    context = context_for(empty_world(), roots=[tmp_path])
    sensor_files.on_save_sensor_data(
        context,
        context.row("save_sensor_data"),
        save_request("out", "frame1"),
    )
    pcd = (tmp_path / "out" / "frame1.pcd").read_bytes()
    header, _, body = pcd.partition(b"DATA binary\n")
    fields = dict(line.split(" ", 1) for line in header.decode().splitlines())
    count = int(fields["POINTS"])
    assert fields["FIELDS"] == "x y z intensity"
    assert count == len(cloud_points(sensor_rows.publish_lidar(context, context.row("lidar"))))
    assert len(body) == 16 * count
    readings = json.loads((tmp_path / "out" / "frame1.json").read_text())
    assert readings["gps"]["status"] == 1
    assert readings["imu"]["linear_acceleration"]["z"] == pytest.approx(9.81, abs=0.01)


def test_save_sensor_data_names_files_after_the_sim_time(tmp_path: Path) -> None:
    world = empty_world()
    world.step()
    save_sensor_data(context_for(world, roots=[tmp_path]), save_request(str(tmp_path)))
    assert sorted(p.name for p in tmp_path.iterdir()) == [
        "sensor_data_10000.json",
        "sensor_data_10000.pcd",
    ]


@pytest.mark.parametrize(
    ("file_dir", "name", "reason"),
    [
        ("/etc", "x", "outside the data roots"),
        ("../", "x", "outside the data roots"),
        ("missing", "x", "not found"),
        (".", "../escape", "not a plain file name"),
        ("d" * 5000, "x", "File name too long"),
        ("a\x00b", "x", "invalid file name"),
    ],
)
def test_save_sensor_data_refuses_paths_outside_the_roots(
    tmp_path: Path, caplog, file_dir, name, reason
) -> None:
    root = tmp_path / "root"
    root.mkdir()
    save_sensor_data(context_for(empty_world(), roots=[root]), save_request(file_dir, name))
    assert list(root.iterdir()) == []
    assert not (tmp_path / "escape.pcd").exists()
    assert reason in caplog.text


def test_save_sensor_data_does_not_follow_a_link_out_of_the_roots(tmp_path: Path, caplog) -> None:
    root, outside = tmp_path / "root", tmp_path / "outside"
    root.mkdir()
    outside.mkdir()
    (root / "frame.pcd").symlink_to(outside / "frame.pcd")
    save_sensor_data(context_for(empty_world(), roots=[root]), save_request(".", "frame"))
    assert list(outside.iterdir()) == []
    assert "outside the data roots" in caplog.text
