"""The sensor rows: /gps, /imu, /lidar3D, /radar and /tf out, /SensorPosControl in.

Readings are taken from the main ego's current state when a row is due (and has a
subscriber or a tap, so the LiDAR is only cast when someone listens). Frames: GPS
in degrees and metres (GPSMessage), IMU in its sensor frame with orientation in the
ENU map frame, LiDAR points in the LiDAR frame, tf from map to base_link to each
sensor's frame_id.
"""

from __future__ import annotations

import logging
from typing import TYPE_CHECKING

from ..context import BridgeContext
from ..protocol.table import Row
from .sensor_messages import gps_message, imu_message, point_cloud, radar_message, tf_bytes
from .sensor_rig import GPS_INDEX, IMU_INDEX, LIDAR_INDEX, finite_mount

if TYPE_CHECKING:
    from ...msgs.typed import morai_26_r1, standard

log = logging.getLogger(__name__)

MOUNT_ARRAYS = ("pose_x", "pose_y", "pose_z", "roll", "pitch", "yaw")


def publish_gps(context: BridgeContext, row: Row) -> morai_26_r1.GPSMessage:
    rig = context.sensors
    header = context.header(rig.frame_ids[GPS_INDEX])
    return gps_message(context.profile, header, rig.gps_fix(context.world))


def publish_imu(context: BridgeContext, row: Row) -> standard.Imu:
    rig = context.sensors
    header = context.header(rig.frame_ids[IMU_INDEX])
    return imu_message(context.profile, header, rig.imu_reading(context.world))


def publish_lidar(context: BridgeContext, row: Row) -> standard.PointCloud2:
    rig = context.sensors
    header = context.header(rig.frame_ids[LIDAR_INDEX])
    return point_cloud(context.profile, header, rig.scan(context.world, context.objects()))


def publish_radar(context: BridgeContext, row: Row) -> morai_26_r1.RadarDetections:
    rig = context.sensors
    header = context.header(rig.frame_ids[rig.radar_index])
    detections = rig.radar_detections(context.world, context.objects())
    return radar_message(context.profile, header, detections)


def publish_tf(context: BridgeContext, row: Row) -> bytes:
    """/tf: its bytes."""
    rig = context.sensors
    return tf_bytes(context.profile, context.stamp_ns(), rig.transforms(context.world))


def on_sensor_pos_control(
    context: BridgeContext, row: Row, message: morai_26_r1.SensorPosControl
) -> None:
    """/SensorPosControl: parallel arrays; entry k moves sensor `sensor_index[k]` (m, rad)."""
    arrays = [message.sensor_index, *(getattr(message, name) for name in MOUNT_ARRAYS)]
    lengths = {len(array) for array in arrays}
    if len(lengths) != 1:
        log.error("%s: the 7 arrays differ in length (%s); ignored", row.name, sorted(lengths))
        return
    for k, index in enumerate(message.sensor_index):
        mount = finite_mount(tuple(float(getattr(message, name)[k]) for name in MOUNT_ARRAYS))
        if mount is None:
            log.error("%s: sensor %d: pose is not finite; ignored", row.name, index)
            continue
        try:
            context.sensors.move(int(index), mount)
        except IndexError as error:
            log.error("%s: %s; ignored", row.name, error)
