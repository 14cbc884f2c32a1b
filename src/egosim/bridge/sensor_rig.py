"""The main ego's sensors at run time: models, their mounts, noise streams and tf frames.

SensorPosControl moves a mount by sensor index (0 GPS, 1 IMU, 2 LiDAR, the order of
SENSOR_KINDS); every reading is taken from the world's current state.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from ..sensors import (
    EgoKinematics,
    GpsFix,
    GpsModel,
    ImuModel,
    ImuReading,
    LidarModel,
    MountPose,
    ObstacleBoxes,
    Transform,
    base_link_to_sensor,
    map_to_base_link,
)
from ..world import World
from ..world.map import GeoReference
from ..world.vehicle import VehicleStatus
from .sensor_settings import SENSOR_KINDS, SensorSettings

GPS_INDEX, IMU_INDEX, LIDAR_INDEX = (SENSOR_KINDS.index(kind) for kind in ("gps", "imu", "lidar"))
MAIN_EGO = 0


def ego_kinematics(status: VehicleStatus) -> EgoKinematics:
    """The IMU's input from the vehicle: body-frame velocity and its time derivative.

    VehicleStatus.acceleration is base_link's (the reference point's) acceleration
    (ax = v̇x - r·vy, ay = v̇y + r·vx);
    the IMU model adds ω × v itself, so it takes the components' derivatives. The yaw
    acceleration is not reported by the vehicle and is taken as 0 (it only matters for
    an IMU mounted off base_link).
    """
    vx, vy, vz = status.velocity
    ax, ay, _ = status.acceleration
    r = status.yaw_rate
    pose = status.pose
    return EgoKinematics(
        roll=pose.roll,
        pitch=pose.pitch,
        yaw=pose.yaw,
        velocity=(vx, vy, vz),
        velocity_rate=(ax + r * vy, ay - r * vx, 0.0),
        angular_velocity=(0.0, 0.0, r),
    )


def obstacle_boxes(world: World) -> ObstacleBoxes:
    """Every object of the world as an upright box standing on its footprint."""
    table = world.objects()
    centres = table.positions.copy()
    centres[:, 2] += table.sizes[:, 2] / 2.0
    return ObstacleBoxes(centres, table.sizes, table.headings)


class SensorRig:
    def __init__(self, settings: SensorSettings, georeference: GeoReference) -> None:
        self.settings = settings
        """What the network settings asked for (SensorPosControl moves mounts later)."""
        gps_seed, imu_seed = np.random.SeedSequence(settings.seed).spawn(2)
        self._gps_rng = np.random.default_rng(gps_seed)
        self._imu_rng = np.random.default_rng(imu_seed)
        self.gps = GpsModel(georeference, settings.gps.mount, settings.gps.noise)
        self.imu = ImuModel(settings.imu.mount, settings.imu.noise)
        self.lidar = LidarModel(settings.lidar.config)
        self.frame_ids = (settings.gps.frame_id, settings.imu.frame_id, settings.lidar.frame_id)
        self._sensor_transforms = self._base_link_to_sensors()

    def mounts(self) -> tuple[MountPose, ...]:
        return (self.gps.mount, self.imu.mount, self.lidar.config.mount)

    def move(self, index: int, mount: MountPose) -> None:
        """Mount sensor `index` at `mount` (IndexError for an index that is not a sensor)."""
        if index == GPS_INDEX:
            self.gps = replace(self.gps, mount=mount)
        elif index == IMU_INDEX:
            self.imu = replace(self.imu, mount=mount)
        elif index == LIDAR_INDEX:
            self.lidar = LidarModel(replace(self.lidar.config, mount=mount))
        else:
            raise IndexError(f"no sensor {index} (0 GPS, 1 IMU, 2 LiDAR)")
        self._sensor_transforms = self._base_link_to_sensors()

    def _base_link_to_sensors(self) -> tuple[Transform, ...]:
        """Worked out when a mount is set, not for every /tf message (mounts rarely move)."""
        return tuple(
            base_link_to_sensor(mount, frame_id)
            for mount, frame_id in zip(self.mounts(), self.frame_ids, strict=True)
        )

    def gps_fix(self, world: World) -> GpsFix:
        return self.gps.measure(world.ego_status(MAIN_EGO).pose, self._gps_rng)

    def imu_reading(self, world: World) -> ImuReading:
        return self.imu.measure(ego_kinematics(world.ego_status(MAIN_EGO)), self._imu_rng)

    def scan(self, world: World) -> np.ndarray:
        """LiDAR points (M, 4) in the sensor frame; the main ego (object 0) is not seen."""
        pose = world.ego_status(MAIN_EGO).pose
        return self.lidar.scan(pose, obstacle_boxes(world), exclude_index=MAIN_EGO)

    def transforms(self, world: World) -> list[Transform]:
        """map -> base_link of the main ego, then base_link -> each sensor."""
        pose = world.ego_status(MAIN_EGO).pose
        return [map_to_base_link(pose), *self._sensor_transforms]


def finite_mount(values: tuple[float, ...]) -> MountPose | None:
    """A mount from (x, y, z, roll, pitch, yaw), or None if any value is not finite."""
    if not all(math.isfinite(v) for v in values):
        return None
    x, y, z, roll, pitch, yaw = values
    return MountPose(x=x, y=y, z=z, roll=roll, pitch=pitch, yaw=yaw)
