"""The main ego's sensors at run time: models, their mounts, noise streams and tf frames.

SensorPosControl moves a mount by sensor index (0 GPS, 1 IMU, 2 LiDAR, the order of
SENSOR_KINDS; then the cameras in the order configured; then the radar); every reading
is taken from the world's current state.

Mounts are MORAI's (from the rear-axle midpoint at wheel-centre height); a sensor sits
on base_link at that origin plus its mount (egosim.world.vehicle.sensor_mount_origin),
worked out for the main ego's model whenever it changes.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from ...sensors import (
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
from ...sensors.camera import OPTICAL_IN_BODY
from ...sensors.radar import RadarDetections, RadarModel
from ...sensors.rotation import quaternion_from_matrix
from ...world import World
from ...world.map import GeoReference
from ...world.traffic import ObjectTable
from ...world.vehicle import VehicleStatus, sensor_mount_origin
from ..protocol.network import NetworkSettings
from ..protocol.sensor_settings import SENSOR_KINDS, CameraSettings, SensorSettings, camera_topic
from ..protocol.table import DEFAULT_CAMERA_TOPIC

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


def sensor_rig_of(settings: NetworkSettings, georeference: GeoReference) -> SensorRig:
    """The main ego's sensors as the network settings configure them, the cameras on the
    camera row's topic."""
    return SensorRig(settings.sensors, georeference, camera_row_topic=settings.row("camera").name)


def obstacle_boxes(table: ObjectTable) -> ObstacleBoxes:
    """Every object of `table` as an upright box standing on its footprint."""
    centres = table.positions.copy()
    centres[:, 2] += table.sizes[:, 2] / 2.0
    return ObstacleBoxes(centres, table.sizes, table.headings)


def on_base_link(mount: MountPose, origin: tuple[float, float, float]) -> MountPose:
    """A MORAI mount placed on base_link: moved by the mount origin, turned as it is."""
    return replace(mount, x=mount.x + origin[0], y=mount.y + origin[1], z=mount.z + origin[2])


class SensorRig:
    def __init__(
        self,
        settings: SensorSettings,
        georeference: GeoReference,
        camera_row_topic: str = DEFAULT_CAMERA_TOPIC,
    ) -> None:
        self.settings = settings
        """What the network settings asked for (SensorPosControl moves mounts later)."""
        gps_seed, imu_seed, radar_seed = np.random.SeedSequence(settings.seed).spawn(3)
        self._gps_rng = np.random.default_rng(gps_seed)
        self._imu_rng = np.random.default_rng(imu_seed)
        self._radar_rng = np.random.default_rng(radar_seed)
        self._georeference = georeference
        self._gps_noise, self._imu_noise = settings.gps.noise, settings.imu.noise
        self._lidar_config = settings.lidar.config
        self._radar_config = settings.radar.config
        self.cameras: tuple[CameraSettings, ...] = settings.cameras
        self._mounts: list[MountPose] = [
            settings.gps.mount,
            settings.imu.mount,
            settings.lidar.config.mount,
            *(camera.config.mount for camera in settings.cameras),
            settings.radar.config.mount,
        ]
        self.camera_topics = tuple(camera_topic(c, camera_row_topic) for c in settings.cameras)
        self.camera_frame_ids = camera_frame_ids(settings.cameras, self.camera_topics)
        self.frame_ids = (
            settings.gps.frame_id,
            settings.imu.frame_id,
            settings.lidar.frame_id,
            *self.camera_frame_ids,
            settings.radar.frame_id,
        )
        self.radar_index = len(self._mounts) - 1
        self.origin: tuple[float, float, float] | None = None
        self._place((0.0, 0.0, 0.0))

    def mounts(self) -> tuple[MountPose, ...]:
        """Every sensor's mount as configured (MORAI's coordinates), by sensor index."""
        return tuple(self._mounts)

    def move(self, index: int, mount: MountPose) -> None:
        """Mount sensor `index` at `mount` (IndexError for an index that is not a sensor)."""
        if not 0 <= index < len(self._mounts):
            raise IndexError(
                f"no sensor {index} (0 GPS, 1 IMU, 2 LiDAR, 3..{2 + len(self.cameras)} cameras, "
                f"{self.radar_index} radar)"
            )
        self._mounts[index] = mount
        assert self.origin is not None
        self._place(self.origin)

    def _follow(self, world: World) -> None:
        """Re-place the sensors if the main ego's model (and so the mount origin) changed."""
        origin = sensor_mount_origin(world.egos[MAIN_EGO].vehicle.model)
        if origin != self.origin:
            self._place(origin)

    def _place(self, origin: tuple[float, float, float]) -> None:
        self.origin = origin
        self._placed = [on_base_link(mount, origin) for mount in self._mounts]
        gps, imu, lidar = self._placed[:3]
        self.gps = GpsModel(self._georeference, gps, self._gps_noise)
        self.imu = ImuModel(imu, self._imu_noise)
        self.lidar = LidarModel(replace(self._lidar_config, mount=lidar))
        self.radar = RadarModel(replace(self._radar_config, mount=self._placed[-1]))
        # Worked out when a mount is set, not for every /tf message (mounts rarely move).
        self._sensor_transforms = tuple(
            base_link_to_sensor(mount, frame_id)
            for mount, frame_id in zip(self._placed, self.frame_ids, strict=True)
        ) + tuple(optical_transform(frame_id) for frame_id in self.camera_frame_ids)

    def placed_camera(self, world: World, k: int) -> MountPose:
        """Camera k on base_link, for the main ego's current model."""
        self._follow(world)
        return self._placed[3 + k]

    def gps_fix(self, world: World) -> GpsFix:
        self._follow(world)
        return self.gps.measure(world.ego_status(MAIN_EGO).pose, self._gps_rng)

    def imu_reading(self, world: World) -> ImuReading:
        self._follow(world)
        return self.imu.measure(ego_kinematics(world.ego_status(MAIN_EGO)), self._imu_rng)

    def scan(self, world: World, objects: ObjectTable) -> np.ndarray:
        """LiDAR points (M, 4) in the sensor frame among `objects` (the world's); the main
        ego (object 0) is not seen."""
        self._follow(world)
        pose = world.ego_status(MAIN_EGO).pose
        return self.lidar.scan(pose, obstacle_boxes(objects), exclude_index=MAIN_EGO)

    def radar_detections(self, world: World, objects: ObjectTable) -> RadarDetections:
        """Radar detections of every one of `objects` (the world's) but the main ego."""
        self._follow(world)
        status = world.ego_status(MAIN_EGO)
        yaw = status.pose.yaw
        vx, vy, _ = status.velocity
        cos, sin = math.cos(yaw), math.sin(yaw)
        velocity = (cos * vx - sin * vy, sin * vx + cos * vy, 0.0)
        return self.radar.detect(
            status.pose,
            velocity,
            status.yaw_rate,
            objects,
            (world.egos[MAIN_EGO].unique_id,),
            self._radar_rng,
        )

    def transforms(self, world: World) -> list[Transform]:
        """map -> base_link of the main ego, then base_link -> each sensor."""
        self._follow(world)
        pose = world.ego_status(MAIN_EGO).pose
        return [map_to_base_link(pose), *self._sensor_transforms]


def optical_transform(camera_frame: str) -> Transform:
    """`<camera>` -> `<camera>_optical`: REP 103's z forward, x right, y down."""
    return Transform(
        camera_frame,
        optical_frame(camera_frame),
        (0.0, 0.0, 0.0),
        quaternion_from_matrix(OPTICAL_IN_BODY),
    )


def optical_frame(camera_frame: str) -> str:
    return f"{camera_frame}_optical"


def camera_frame_ids(
    cameras: tuple[CameraSettings, ...], topics: tuple[str, ...]
) -> tuple[str, ...]:
    """Each camera's frame_id: its own, else `Camera`, or `Camera-<n>` (n counted from 1
    over the cameras of its topic) when several cameras share a topic, as in MORAI."""
    ids = []
    for k, camera in enumerate(cameras):
        if camera.frame_id is not None:
            ids.append(camera.frame_id)
            continue
        sharing = [j for j, topic in enumerate(topics) if topic == topics[k]]
        ids.append("Camera" if len(sharing) == 1 else f"Camera-{sharing.index(k) + 1}")
    return tuple(ids)


def finite_mount(values: tuple[float, ...]) -> MountPose | None:
    """A mount from (x, y, z, roll, pitch, yaw), or None if any value is not finite."""
    if not all(math.isfinite(v) for v in values):
        return None
    x, y, z, roll, pitch, yaw = values
    return MountPose(x=x, y=y, z=z, roll=roll, pitch=pitch, yaw=yaw)
