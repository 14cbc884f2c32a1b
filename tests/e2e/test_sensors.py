"""A MORAI client localises from /gps and /imu and sees the world in /lidar3D and /tf."""

from __future__ import annotations

import json
import math

import pyproj
import pytest

from egosim.world.map import build_builtin_map
from egosim.world.vehicle import DEFAULT_EGO_MODEL, sensor_mount_origin, vehicle_model
from tests.ros1.helpers import wait_until

pytestmark = pytest.mark.ros

EGO = ("/Ego_topic", "morai_msgs/EgoVehicleStatus")
GPS = ("/gps", "morai_msgs/GPSMessage")
IMU = ("/imu", "sensor_msgs/Imu")
LIDAR = ("/lidar3D", "sensor_msgs/PointCloud2")
TF = ("/tf", "tf2_msgs/TFMessage")
SAVE = ("/SaveSensorData", "morai_msgs/SaveSensorData")
STANDARD_GRAVITY = 9.80665


def test_gps_round_trip_gives_back_the_ego_position(egosim, rospy_client) -> None:
    client = rospy_client(egosim("--map", "straight"))
    client.subscribe(*GPS)
    client.subscribe(*EGO)
    fix = client.next_message(GPS[0])
    ego = client.next_message(EGO[0])
    zone = build_builtin_map("straight").georef.utm_zone
    utm = pyproj.Proj(proj="utm", zone=zone, ellps="WGS84")
    east, north = utm(fix["longitude"], fix["latitude"])
    # The default antenna (x 0, y 0) stands on MORAI's mount origin, the rear axle's
    # midpoint, behind the ego's reported position.
    behind = sensor_mount_origin(vehicle_model(DEFAULT_EGO_MODEL))[0]
    heading = math.radians(ego["heading"])
    expected_x = ego["position"]["x"] + behind * math.cos(heading)
    expected_y = ego["position"]["y"] + behind * math.sin(heading)
    assert east - fix["eastOffset"] == pytest.approx(expected_x, abs=0.01)
    assert north - fix["northOffset"] == pytest.approx(expected_y, abs=0.01)
    assert fix["status"] == 1
    assert fix["header"]["frame_id"] == "gps"


def test_imu_at_rest_reads_gravity_and_the_heading(egosim, rospy_client) -> None:
    client = rospy_client(egosim("--map", "straight"))
    client.subscribe(*IMU)
    client.subscribe(*EGO)
    imu = client.next_message(IMU[0])
    heading = math.radians(client.next_message(EGO[0])["heading"])
    assert imu["linear_acceleration"]["z"] == pytest.approx(STANDARD_GRAVITY, abs=1e-6)
    assert imu["linear_acceleration"]["x"] == pytest.approx(0.0, abs=1e-6)
    assert imu["linear_acceleration"]["y"] == pytest.approx(0.0, abs=1e-6)
    assert [imu["angular_velocity"][a] for a in "xyz"] == pytest.approx([0.0] * 3, abs=1e-9)
    q = imu["orientation"]
    assert 2 * math.atan2(q["z"], q["w"]) == pytest.approx(heading, abs=1e-6)


def test_lidar_cloud_on_open_ground_and_its_tf(egosim, rospy_client) -> None:
    client = rospy_client(egosim("--map", "straight"))
    client.subscribe(*LIDAR)
    client.subscribe(*TF)
    cloud = client.next_message(LIDAR[0])
    # The default 16 x 1800 beams from 1.8 m above MORAI's mount origin (the wheel radius
    # above the road): the 7 channels from -15 to -3 deg meet the ground within 100 m
    # (-1 deg does so beyond 103 m); the others miss.
    assert (cloud["height"], cloud["width"]) == (1, 7 * 1800)
    assert [f["name"] for f in cloud["fields"]] == ["x", "y", "z", "intensity"]
    assert cloud["point_step"] == 16
    assert cloud["data"] == {"bytes": 16 * 7 * 1800}
    assert cloud["header"]["frame_id"] == "lidar"
    transforms = client.next_message(TF[0])["transforms"]
    pairs = {(t["header"]["frame_id"], t["child_frame_id"]) for t in transforms}
    assert pairs == {
        ("map", "base_link"),
        ("base_link", "gps"),
        ("base_link", "imu"),
        ("base_link", "lidar"),
        ("base_link", "Camera"),
        ("Camera", "Camera_optical"),
        ("base_link", "radar"),
    }


def test_save_sensor_data_writes_files_in_the_data_root(egosim, rospy_client) -> None:
    simulator = egosim("--map", "straight")
    client = rospy_client(simulator)
    request = {"is_custom_file_name": True, "custom_file_name": "snap", "file_dir": "."}
    client.publish(*SAVE, request)
    readings = simulator.data_root / "snap.json"

    def saved() -> bool:
        try:
            return json.loads(readings.read_text())["gps"]["status"] == 1
        except (FileNotFoundError, json.JSONDecodeError):  # not (completely) written yet
            return False

    wait_until(saved)
    assert (simulator.data_root / "snap.pcd").read_bytes().startswith(b"# .PCD v0.7")
