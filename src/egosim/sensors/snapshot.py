"""JSON-ready record of one GPS fix and IMU reading, as saved by SaveSensorData."""

from __future__ import annotations

from typing import TypedDict

from egosim.sensors.gps import GpsFix
from egosim.sensors.imu import ImuReading


class GpsRecord(TypedDict):
    """GPSMessage's field names, camelCase as the message spells them."""

    latitude: float
    longitude: float
    altitude: float
    eastOffset: float
    northOffset: float
    status: int


class ImuRecord(TypedDict):
    """sensor_msgs/Imu's field names; vectors and the quaternion by axis name."""

    orientation: dict[str, float]
    orientation_covariance: list[float]
    angular_velocity: dict[str, float]
    angular_velocity_covariance: list[float]
    linear_acceleration: dict[str, float]
    linear_acceleration_covariance: list[float]


class GpsImuSnapshot(TypedDict):
    stamp: float
    gps: GpsRecord
    imu: ImuRecord


def gps_imu_snapshot(stamp_s: float, gps: GpsFix, imu: ImuReading) -> GpsImuSnapshot:
    """Plain dicts, lists and numbers; field names follow GPSMessage and sensor_msgs/Imu."""
    return {
        "stamp": stamp_s,
        "gps": {
            "latitude": gps.latitude,
            "longitude": gps.longitude,
            "altitude": gps.altitude,
            "eastOffset": gps.east_offset,
            "northOffset": gps.north_offset,
            "status": gps.status,
        },
        "imu": {
            "orientation": dict(zip("xyzw", imu.orientation, strict=True)),
            "orientation_covariance": list(imu.orientation_covariance),
            "angular_velocity": dict(zip("xyz", imu.angular_velocity, strict=True)),
            "angular_velocity_covariance": list(imu.angular_velocity_covariance),
            "linear_acceleration": dict(zip("xyz", imu.linear_acceleration, strict=True)),
            "linear_acceleration_covariance": list(imu.linear_acceleration_covariance),
        },
    }
