"""GPS, IMU, LiDAR and tf readings as the messages MORAI SIM publishes."""

from __future__ import annotations

import functools
from collections.abc import Iterable
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from ...sensors import GpsFix, ImuReading, Transform
from ...sensors.imu import Covariance
from ...sensors.radar import RadarDetections
from ..protocol.messages import point, quaternion, vector3
from ..protocol.units import deg

if TYPE_CHECKING:
    from ...msgs.typed import morai_26_r1, standard
    from ..protocol.releases import CanonicalProfile

POINT_FIELDS = ("x", "y", "z", "intensity")
FLOAT32 = 7  # sensor_msgs/PointField datatype code


def gps_message(
    profile: CanonicalProfile, header: standard.Header, fix: GpsFix
) -> morai_26_r1.GPSMessage:
    return profile.message("morai_msgs/GPSMessage").make(
        header=header,
        latitude=fix.latitude,
        longitude=fix.longitude,
        altitude=fix.altitude,
        eastOffset=fix.east_offset,
        northOffset=fix.north_offset,
        status=fix.status,
    )


def imu_message(
    profile: CanonicalProfile, header: standard.Header, reading: ImuReading
) -> standard.Imu:
    return profile.message("sensor_msgs/Imu").make(
        header=header,
        orientation=quaternion(profile, reading.orientation),
        orientation_covariance=covariance_array(reading.orientation_covariance),
        angular_velocity=vector3(profile, reading.angular_velocity),
        angular_velocity_covariance=covariance_array(reading.angular_velocity_covariance),
        linear_acceleration=vector3(profile, reading.linear_acceleration),
        linear_acceleration_covariance=covariance_array(reading.linear_acceleration_covariance),
    )


@functools.lru_cache(maxsize=16)
def covariance_array(covariance: Covariance) -> npt.NDArray[np.float64]:
    """A covariance as a message field, made once per value (a model's covariances do not
    change between readings) and read-only, as messages share it."""
    array = np.array(covariance, dtype=np.float64)
    array.flags.writeable = False
    return array


def point_cloud(
    profile: CanonicalProfile, header: standard.Header, points: np.ndarray
) -> standard.PointCloud2:
    """sensor_msgs/PointCloud2 of (M, 4) float32 points x, y, z, intensity (unorganised)."""
    cloud = np.ascontiguousarray(points, dtype="<f4")
    field_type = profile.message("sensor_msgs/PointField")
    fields = [
        field_type.make(name=name, offset=4 * index, datatype=FLOAT32, count=1)
        for index, name in enumerate(POINT_FIELDS)
    ]
    return profile.message("sensor_msgs/PointCloud2").make(
        header=header,
        height=1,
        width=len(cloud),
        fields=fields,
        is_bigendian=False,
        point_step=16,
        row_step=16 * len(cloud),
        data=cloud.view(np.uint8).reshape(-1),
        is_dense=True,
    )


def tf_bytes(profile: CanonicalProfile, stamp_ns: int, transforms: Iterable[Transform]) -> bytes:
    """tf2_msgs/TFMessage's bytes: each transform stamped `stamp_ns`."""
    sec, nanosec = divmod(stamp_ns, 1_000_000_000)
    stamped = profile.message("geometry_msgs/TransformStamped").flat().pack
    return (
        profile.message("tf2_msgs/TFMessage")
        .flat()
        .pack(
            [
                stamped(0, sec, nanosec, t.parent_frame, t.child_frame, *t.translation, *t.rotation)
                for t in transforms
            ]
        )
    )


def radar_message(
    profile: CanonicalProfile, header: standard.Header, detections: RadarDetections
) -> morai_26_r1.RadarDetections:
    """morai_msgs/RadarDetections: azimuth in degrees, detection_id the object's id (16 bit)."""
    detection = profile.message("morai_msgs/RadarDetection").make
    return profile.message("morai_msgs/RadarDetections").make(
        header=header,
        detections=[
            detection(
                detection_id=uid & 0xFFFF,
                position=point(profile, position),
                azimuth=deg(azimuth),
                rangerate=rate,
                amplitude=amplitude,
            )
            for uid, position, azimuth, rate, amplitude in zip(
                detections.unique_ids.tolist(),
                detections.positions.tolist(),
                detections.azimuths.tolist(),
                detections.range_rates.tolist(),
                detections.amplitudes.tolist(),
                strict=True,
            )
        ],
    )
