"""GPS receiver: the antenna's position as WGS84 latitude, longitude, altitude.

Matches morai_msgs/GPSMessage: eastOffset/northOffset are the map's local
origin in UTM, so UTM(latitude, longitude) - (eastOffset, northOffset) is the
antenna's position in the map frame.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass, field

import numpy as np

from egosim.sensors.frames import MountFrame, MountPose
from egosim.sensors.last_reading import LastReading
from egosim.sensors.noise import gaussian, require_non_negative
from egosim.world.map.georef import GeoReference
from egosim.world.vehicle import Pose

GPS_STATUS_FIX = 1
"""GPSMessage.status of a valid fix (0 would mean no fix; the model always has one)."""


@dataclass(frozen=True)
class GpsNoise:
    """Zero-mean Gaussian position error, standard deviations in metres.

    horizontal_std_m applies to east and north independently.
    """

    horizontal_std_m: float = 0.0
    vertical_std_m: float = 0.0

    def __post_init__(self) -> None:
        require_non_negative("GPS noise std", [self.horizontal_std_m, self.vertical_std_m])

    @property
    def enu_std_m(self) -> np.ndarray:
        return np.array([self.horizontal_std_m, self.horizontal_std_m, self.vertical_std_m])


@dataclass(frozen=True)
class GpsFix:
    latitude: float
    """Degrees, WGS84 (or the georeference's ellipsoid)."""
    longitude: float
    """Degrees."""
    altitude: float
    """Metres above the ellipsoid: origin_up + z."""
    east_offset: float
    """UTM easting of the map origin, m."""
    north_offset: float
    """UTM northing of the map origin, m."""
    status: int


@dataclass(frozen=True)
class GpsModel:
    georeference: GeoReference
    mount: MountPose = field(default_factory=MountPose)
    noise: GpsNoise = field(default_factory=GpsNoise)

    @functools.cached_property
    def _mount_frame(self) -> MountFrame:
        return MountFrame(self.mount)

    @functools.cached_property
    def _enu_std_m(self) -> np.ndarray | None:
        """The noise's std, None for none."""
        std = self.noise.enu_std_m
        return std if np.any(std) else None

    def antenna_position(self, vehicle_pose: Pose) -> np.ndarray:
        """Antenna in the map frame: vehicle position + R_vehicle @ mount offset."""
        return self._mount_frame.origin_in_map(vehicle_pose)

    def measure(self, vehicle_pose: Pose, rng: np.random.Generator | None = None) -> GpsFix:
        """A fix of the antenna; `rng` is required only when noise is configured."""
        antenna = self.antenna_position(vehicle_pose)
        if self._enu_std_m is not None:
            x, y, z = (antenna + gaussian(self._enu_std_m, rng, "GPS")).tolist()
        else:  # gaussian's zeros, added on plain floats (-0.0 + 0.0 is 0.0 there too)
            east, north, up = antenna.tolist()
            x, y, z = east + 0.0, north + 0.0, up + 0.0
        return self._last_fix.of((x, y, z), lambda: self._fix_at(x, y, z))

    @functools.cached_property
    def _last_fix(self) -> LastReading[GpsFix]:
        return LastReading(3)

    def _fix_at(self, x: float, y: float, z: float) -> GpsFix:
        """The fix of an antenna at (x, y, z) in the map frame, m."""
        latitude, longitude, altitude = self.georeference.local_to_geodetic(x, y, z)
        return GpsFix(
            latitude=latitude,
            longitude=longitude,
            altitude=altitude,
            east_offset=self.georeference.origin_east,
            north_offset=self.georeference.origin_north,
            status=GPS_STATUS_FIX,
        )
