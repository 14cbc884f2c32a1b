"""The network settings file's sensors: section: mounts, noise, LiDAR geometry, errors."""

from __future__ import annotations

import math

import pytest

from egosim.bridge.protocol.network import default_network_settings, parse_network_settings
from egosim.bridge.protocol.sensor_settings import SensorSettings
from egosim.sensors import GpsNoise, LidarConfig, MountPose
from egosim.yamltext import YamlFileError

FULL = """\
rows:
  lidar: {name: /velodyne_points, rate_hz: 20}
sensors:
  seed: 7
  gps:
    frame_id: gnss
    mount: {x: 1.0, z: 2.0}
    noise: {horizontal_std_m: 0.5, vertical_std_m: 1.0}
  imu:
    mount: {yaw_deg: 90}
    noise:
      angular_velocity_std_rad_s: 0.01
      linear_acceleration_bias_m_s2: [0.1, 0.0, 0.0]
  lidar:
    channels: 32
    min_elevation_deg: -30
    max_elevation_deg: 10
    horizontal_resolution_deg: 0.5
    max_range_m: 120
"""


def test_defaults_are_a_gps_imu_and_vlp16_like_lidar() -> None:
    sensors = default_network_settings().sensors
    assert sensors == SensorSettings()
    assert sensors.lidar.config == LidarConfig()
    assert {
        row.key: row.name
        for row in default_network_settings().rows
        if row.key in ("gps", "imu", "lidar", "tf", "clock")
    } == {
        "gps": "/gps",
        "imu": "/imu",
        "lidar": "/lidar3D",
        "tf": "/tf",
        "clock": "/clock",
    }


def test_every_field_of_the_section_is_read() -> None:
    settings = parse_network_settings(FULL, "net.yaml")
    sensors = settings.sensors
    assert settings.row("lidar").name == "/velodyne_points"
    assert settings.row("lidar").rate_hz == 20
    assert sensors.seed == 7
    assert sensors.gps.frame_id == "gnss"
    assert sensors.gps.mount == MountPose(x=1.0, z=2.0)
    assert sensors.gps.noise == GpsNoise(horizontal_std_m=0.5, vertical_std_m=1.0)
    assert sensors.imu.mount.yaw == pytest.approx(math.pi / 2)
    assert sensors.imu.noise.angular_velocity_std_rad_s == 0.01
    assert sensors.imu.noise.linear_acceleration_bias_m_s2 == (0.1, 0.0, 0.0)
    lidar = sensors.lidar.config
    assert (lidar.channels, lidar.horizontal_steps, lidar.max_range_m) == (32, 720, 120)
    assert (lidar.min_elevation_deg, lidar.max_elevation_deg) == (-30, 10)
    assert lidar.mount == LidarConfig().mount


@pytest.mark.parametrize(
    ("text", "line", "field", "problem"),
    [
        ("sensors:\n  sonar: {}\n", 2, "sensors.sonar", "unknown field"),
        ("sensors:\n  seed: -1\n", 2, "sensors.seed", "non-negative integer"),
        ("sensors:\n  gps:\n    mount: {x: fast}\n", 3, "sensors.gps.mount.x", "expected a number"),
        ("sensors:\n  gps:\n    mount: {roll: 1}\n", 3, "sensors.gps.mount.roll", "unknown field"),
        ("sensors:\n  gps:\n    noise: {horizontal_std_m: -1}\n", 3, "sensors.gps.noise", ">= 0"),
        (
            "sensors:\n  imu:\n    noise:\n      linear_acceleration_bias_m_s2: [1, 2]\n",
            4,
            "sensors.imu.noise.linear_acceleration_bias_m_s2",
            "3 numbers",
        ),
        ("sensors:\n  lidar:\n    channels: 2.5\n", 3, "sensors.lidar.channels", "integer"),
        (
            "sensors:\n  lidar:\n    horizontal_resolution_deg: 0.7\n",
            2,
            "sensors.lidar",
            "divide 360",
        ),
        (
            "sensors:\n  lidar:\n    horizontal_resolution_deg: 0\n",
            3,
            "sensors.lidar.horizontal_resolution_deg",
            "> 0",
        ),
        ("sensors:\n  lidar:\n    frame_id: a/b\n", 3, "sensors.lidar.frame_id", "tf frame name"),
        (
            "sensors:\n  lidar:\n    channels: 1000000000\n",
            3,
            "sensors.lidar.channels",
            "must be <= 256",
        ),
        (
            "sensors:\n  lidar:\n    channels: 256\n    horizontal_resolution_deg: 0.05\n",
            2,
            "sensors.lidar",
            "rays a scan (at most 1000000)",
        ),
        (
            "sensors:\n  gps:\n    mount: {z: 1.0e+300}\n",
            3,
            "sensors.gps.mount.z",
            "must be <= 100",
        ),
        (
            "sensors:\n  imu:\n    noise: {linear_acceleration_bias_m_s2: [0, 0, 1.0e+9]}\n",
            3,
            "sensors.imu.noise.linear_acceleration_bias_m_s2.2",
            "must be <= 1000",
        ),
        ("rows:\n  lidar: {rate_hz: 1.0e+9}\n", 2, "rows.lidar.rate_hz", "0..1000 Hz"),
    ],
)
def test_errors_name_the_file_line_and_field(text, line, field, problem) -> None:
    with pytest.raises(YamlFileError) as raised:
        parse_network_settings(text, "net.yaml")
    message = str(raised.value)
    assert f"net.yaml:{line}" in message
    assert field in message
    assert problem in message
