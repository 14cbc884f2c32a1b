"""Sensor models over world state: GPS, IMU, 3D LiDAR, cameras, radar and their tf frames.

Pure and deterministic: SI units, no I/O; randomness only through a numpy
Generator the caller passes in.
"""

from egosim.sensors.errors import (
    MissingRandomGeneratorError,
    RendererUnavailableError,
    SensorConfigError,
    SensorError,
)
from egosim.sensors.frames import (
    MountPose,
    Transform,
    base_link_to_sensor,
    map_to_base_link,
    sensor_in_map,
)
from egosim.sensors.gps import GPS_STATUS_FIX, GpsFix, GpsModel, GpsNoise
from egosim.sensors.imu import STANDARD_GRAVITY, EgoKinematics, ImuModel, ImuNoise, ImuReading
from egosim.sensors.lidar import LidarConfig, LidarIntensity, LidarModel
from egosim.sensors.pcd import encode_pcd
from egosim.sensors.raycast import ObstacleBoxes
from egosim.sensors.snapshot import gps_imu_snapshot
from egosim.world.vehicle import Pose

__all__ = [
    "GPS_STATUS_FIX",
    "STANDARD_GRAVITY",
    "EgoKinematics",
    "GpsFix",
    "GpsModel",
    "GpsNoise",
    "ImuModel",
    "ImuNoise",
    "ImuReading",
    "LidarConfig",
    "LidarIntensity",
    "LidarModel",
    "MissingRandomGeneratorError",
    "MountPose",
    "ObstacleBoxes",
    "Pose",
    "RendererUnavailableError",
    "SensorConfigError",
    "SensorError",
    "Transform",
    "base_link_to_sensor",
    "encode_pcd",
    "gps_imu_snapshot",
    "map_to_base_link",
    "sensor_in_map",
]
