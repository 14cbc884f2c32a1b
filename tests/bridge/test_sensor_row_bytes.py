"""The sensor rows' bytes: /gps, /imu, /lidar3D, /radar and /tf of a busy town with an
ego parked, then driving, are, message for message, the bytes they were before their builders were
made cheaper (tests/data/bridge/sensor_row_bytes.json), and the compiled path gives the
numpy path's bytes."""

from __future__ import annotations

import hashlib
import json
from dataclasses import replace
from pathlib import Path
from typing import Any

import pytest

from egosim.bridge import HANDLERS, default_network_settings, simulation_context
from egosim.bridge.protocol.network import NetworkSettings
from egosim.bridge.protocol.sensor_settings import (
    GpsSettings,
    ImuSettings,
    LidarSettings,
    RadarSettings,
    SensorSettings,
)
from egosim.sensors import GpsNoise, ImuNoise, LidarConfig, MountPose
from egosim.sensors.radar import RadarConfig, RadarNoise
from egosim.world import World, kernels
from egosim.world.map import build_builtin_map
from egosim.world.scenario import parse_scenario
from egosim.world.vehicle import ControlCommand, LongitudinalMode
from tests.compiled_paths import busy_town, drive

REFERENCE = Path(__file__).parents[1] / "data" / "bridge" / "sensor_row_bytes.json"
ROWS = {
    "gps": "morai_msgs/GPSMessage",
    "imu": "sensor_msgs/Imu",
    "lidar": "sensor_msgs/PointCloud2",
    "radar": "morai_msgs/RadarDetections",
    "tf": "tf2_msgs/TFMessage",
}
TICKS = 300
PARKED_TICKS = 60
DIGEST_CHARS = 16

# Every mount turned and moved off base_link, every noise on, a LiDAR tilted down with
# close and far range gates: the lever-arm, rotation and noise terms all count.
NOISY_TILTED = SensorSettings(
    seed=5,
    gps=GpsSettings(
        mount=MountPose(x=1.2, y=-0.3, z=1.6, yaw=0.2),
        noise=GpsNoise(horizontal_std_m=0.4, vertical_std_m=0.9),
    ),
    imu=ImuSettings(
        mount=MountPose(x=0.8, y=0.25, z=0.5, roll=0.03, pitch=-0.05, yaw=1.1),
        noise=ImuNoise(
            orientation_std_rad=0.002,
            angular_velocity_std_rad_s=0.01,
            linear_acceleration_std_m_s2=0.05,
            angular_velocity_bias_rad_s=(0.001, -0.002, 0.0005),
            linear_acceleration_bias_m_s2=(0.02, 0.0, -0.03),
        ),
    ),
    lidar=LidarSettings(
        config=LidarConfig(
            channels=24,
            min_elevation_deg=-25.0,
            max_elevation_deg=10.0,
            horizontal_resolution_deg=0.4,
            min_range_m=2.0,
            max_range_m=45.0,
            mount=MountPose(x=1.0, y=0.1, z=1.9, roll=0.02, pitch=0.06, yaw=-0.4),
        )
    ),
    cameras=(),
    radar=RadarSettings(
        config=RadarConfig(
            horizontal_fov_deg=120.0,
            max_detections=5,
            mount=MountPose(x=3.6, y=0.4, z=0.3, yaw=0.3),
            noise=RadarNoise(range_std_m=0.2, azimuth_std_rad=0.01, range_rate_std_m_s=0.1),
        )
    ),
)
SETTINGS = {"default": None, "noisy and tilted": NOISY_TILTED}


def scenario(town: Any) -> dict[str, Any]:
    """tests/compiled_paths.py's busy town, the ego standing, with a box taller than the
    LiDAR beside the ego's lane (rising beams meet it) and one straddling its bearing of
    +-180 degrees."""
    scene = busy_town(town)
    scene["ego"]["speed_mps"] = 0.0
    behind = town.pose_at("R5_E_1", 1.0)
    beside = town.pose_at("R5_E_1", 60.0)
    scene["obstacles"] += [
        {
            "model": "Box",
            "pose": {"x": beside[0], "y": beside[1] + 4.5},
            "size": {"length": 8.0, "width": 2.5, "height": 4.5},
        },
        {
            "model": "Box",
            "pose": {"x": behind[0] - 7.0, "y": behind[1]},
            "size": {"length": 2.0, "width": 2.0, "height": 2.0},
        },
    ]
    return scene


def network_settings(sensors: SensorSettings | None) -> NetworkSettings:
    settings = default_network_settings()
    return settings if sensors is None else replace(settings, sensors=sensors)


def published_bytes(sensors: SensorSettings | None) -> dict[str, list[bytes]]:
    """Every tick's serialised sensor rows, each row built at every tick: parked for
    PARKED_TICKS, then driving ahead, weaving (tests/compiled_paths.py)."""
    town = build_builtin_map("town")
    world = World(town, parse_scenario(scenario(town), "busy town"))
    context = simulation_context(world, settings=network_settings(sensors))
    messages: dict[str, list[bytes]] = {key: [] for key in ROWS}
    for k in range(TICKS):
        if k < PARKED_TICKS:  # standing still while the traffic moves
            world.egos[0].vehicle.command(ControlCommand(mode=LongitudinalMode.VELOCITY))
        else:
            drive(world, k)
        context.tick(world.physics_step_s)
        for key, type_name in ROWS.items():
            message = HANDLERS.publishers[key](context, context.row(key))
            messages[key].append(context.profile.message(type_name).serialize(message))
    return messages


def digests(messages: dict[str, list[bytes]]) -> dict[str, list[str]]:
    return {
        key: [hashlib.sha256(data).hexdigest()[:DIGEST_CHARS] for data in row]
        for key, row in messages.items()
    }


def first_difference(got: list[str], expected: list[str]) -> str:
    differing = [k for k, (a, b) in enumerate(zip(got, expected, strict=True)) if a != b]
    return f"{len(differing)} of {len(got)} differ, the first at tick {differing[0]}"


@pytest.mark.parametrize("name", SETTINGS)
def test_sensor_rows_publish_the_bytes_they_published_before(name: str) -> None:
    """REFERENCE was written by the builders before they were made cheaper, running
    this module's scenario through `write_reference`. Bit for bit on the machine that
    wrote it: another CPU's maths library may round a last digit differently."""
    expected = json.loads(REFERENCE.read_text())[name]
    got = digests(published_bytes(SETTINGS[name]))
    for key in ROWS:
        assert got[key] == expected[key], (
            f"{name} {key}: {first_difference(got[key], expected[key])} (on another CPU than"
            " the reference's, numpy's arctangents may differ: re-record with write_reference"
            " from a commit whose bytes are trusted)"
        )
    scans = set(got["lidar"])
    assert len(scans) > TICKS // 2  # the scene moves under the LiDAR


@pytest.mark.skipif(
    not kernels.AVAILABLE, reason="no compiled path: numba missing or EGOSIM_COMPILED=0"
)
@pytest.mark.parametrize("name", SETTINGS)
def test_compiled_and_numpy_sensor_rows_publish_identical_bytes(
    name: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(kernels, "ACTIVE", True)
    compiled = published_bytes(SETTINGS[name])
    monkeypatch.setattr(kernels, "ACTIVE", False)
    plain = published_bytes(SETTINGS[name])
    for key in ROWS:
        assert compiled[key] == plain[key], f"{name} {key}: " + first_difference(
            *digests({"c": compiled[key], "p": plain[key]}).values()
        )


def write_reference(path: Path) -> None:
    """REFERENCE from these builders: `python -c "from tests.bridge.test_sensor_row_bytes
    import REFERENCE, write_reference; write_reference(REFERENCE)"` in the worktree."""
    reference = {name: digests(published_bytes(sensors)) for name, sensors in SETTINGS.items()}
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(reference, indent=0) + "\n")
