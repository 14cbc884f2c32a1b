"""Poses and the transforms map -> base_link -> sensor.

The map frame is ENU (x east, y north, z up). base_link is the vehicle body
frame (x forward, y left, z up). A sensor frame is placed on base_link by a
MountPose. A vehicle's pose is the world's (its base_link in the map). The
transforms are the ones a tf2_msgs/TFMessage carries: the child
frame's origin and orientation expressed in the parent frame.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from egosim.sensors.rotation import Matrix3, Quaternion, quaternion_from_matrix, rotation_matrix
from egosim.world.vehicle import Pose

Vector3 = npt.NDArray[np.float64]


@dataclass(frozen=True)
class MountPose(Pose):
    """A sensor frame relative to base_link (x forward, y left, z up)."""


def translation_of(pose: Pose) -> Vector3:
    return np.array([pose.x, pose.y, pose.z], dtype=np.float64)


def rotation_of(pose: Pose) -> Matrix3:
    """Rotation taking vectors of the posed frame into its parent frame."""
    return rotation_matrix(pose.roll, pose.pitch, pose.yaw)


@dataclass(frozen=True)
class Transform:
    """Child frame in the parent frame: translation (m) and quaternion (x, y, z, w)."""

    parent_frame: str
    child_frame: str
    translation: tuple[float, float, float]
    rotation: Quaternion


def transform_of(pose: Pose, parent_frame: str, child_frame: str) -> Transform:
    """The tf transform parent -> child for a child frame placed at `pose`."""
    return Transform(
        parent_frame=parent_frame,
        child_frame=child_frame,
        translation=(float(pose.x), float(pose.y), float(pose.z)),
        rotation=quaternion_from_matrix(rotation_of(pose)),
    )


def map_to_base_link(
    vehicle_pose: Pose, map_frame: str = "map", base_frame: str = "base_link"
) -> Transform:
    return transform_of(vehicle_pose, map_frame, base_frame)


def base_link_to_sensor(
    mount: MountPose, sensor_frame: str, base_frame: str = "base_link"
) -> Transform:
    return transform_of(mount, base_frame, sensor_frame)


def sensor_in_map(vehicle_pose: Pose, mount: MountPose) -> tuple[Vector3, Matrix3]:
    """Origin (map, m) and rotation (sensor -> map) of a mounted sensor."""
    return MountFrame(mount).in_map(vehicle_pose)


class MountFrame:
    """A mount's offset (base_link, m) and rotation, worked out once for a sensor that
    reads many times; the same arithmetic as sensor_in_map."""

    def __init__(self, mount: MountPose) -> None:
        self.mount = mount
        self.offset = translation_of(mount)
        self.rotation = rotation_of(mount)

    def in_map(self, vehicle_pose: Pose) -> tuple[Vector3, Matrix3]:
        """Origin (map, m) and rotation (sensor -> map) of the sensor."""
        vehicle_rotation = rotation_of(vehicle_pose)
        return self._origin(vehicle_pose, vehicle_rotation), vehicle_rotation @ self.rotation

    def origin_in_map(self, vehicle_pose: Pose) -> Vector3:
        """The sensor's origin in the map, m: vehicle position + R_vehicle @ offset."""
        return self._origin(vehicle_pose, rotation_of(vehicle_pose))

    def _origin(self, vehicle_pose: Pose, vehicle_rotation: Matrix3) -> Vector3:
        origin: Vector3 = translation_of(vehicle_pose) + vehicle_rotation @ self.offset
        return origin
