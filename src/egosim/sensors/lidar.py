"""Spinning multi-channel 3D LiDAR, cast instantaneously against boxes and ground.

Beams: `channels` elevations evenly spaced over [min, max] and azimuths every
`horizontal_resolution_deg` over 360 deg, starting at the sensor's +x and
turning counter-clockwise (towards +y). Points come out azimuth-major (all
channels of the first azimuth, then the next), in the sensor frame, one per
beam whose nearest hit lies within [min_range, max_range]. A hit closer than
min_range blocks the beam and yields no point, as on a real unit. A whole scan
is taken at one instant (no motion distortion).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt

from egosim.sensors.errors import SensorConfigError
from egosim.sensors.frames import MountFrame, MountPose
from egosim.sensors.raycast import ObstacleBoxes, RayFan, Surface, cast_fan, cast_rays
from egosim.world import kernels
from egosim.world.arrays import FloatArray
from egosim.world.kernels.lidar_returns import lidar_intensities, lidar_returns
from egosim.world.vehicle import Pose

DEFAULT_LIDAR_MOUNT = MountPose(x=0.0, y=0.0, z=1.8)
"""On the roof above base_link, m."""


@dataclass(frozen=True)
class LidarIntensity:
    """intensity = scale * reflectivity(surface) * |cos(incidence)| * exp(-2 * extinction * r).

    A Lambertian surface seen through a uniformly absorbing atmosphere (the
    two-way term of the lidar equation), scaled to 0..255 as calibrated
    reflectivity is on common units.
    """

    ground_reflectivity: float = 0.2
    object_reflectivity: float = 0.6
    extinction_per_m: float = 0.005
    scale: float = 255.0

    def of(
        self, surface: npt.NDArray[np.int8], cos_incidence: FloatArray, distance: FloatArray
    ) -> FloatArray:
        reflectivity = np.where(
            surface == Surface.OBJECT, self.object_reflectivity, self.ground_reflectivity
        )
        return (
            self.scale
            * reflectivity
            * cos_incidence
            * np.exp(-2.0 * self.extinction_per_m * distance)
        )


@dataclass(frozen=True)
class LidarConfig:
    """Defaults describe a VLP-16-like unit."""

    channels: int = 16
    min_elevation_deg: float = -15.0
    max_elevation_deg: float = 15.0
    horizontal_resolution_deg: float = 0.2
    min_range_m: float = 0.5
    max_range_m: float = 100.0
    rate_hz: float = 10.0
    mount: MountPose = DEFAULT_LIDAR_MOUNT
    intensity: LidarIntensity = field(default_factory=LidarIntensity)

    def __post_init__(self) -> None:
        if self.channels < 1:
            raise SensorConfigError(f"channels must be >= 1, got {self.channels}")
        if not -90.0 <= self.min_elevation_deg <= self.max_elevation_deg <= 90.0:
            raise SensorConfigError("elevations must satisfy -90 <= min <= max <= 90 deg")
        if self.channels > 1 and self.min_elevation_deg == self.max_elevation_deg:
            raise SensorConfigError("several channels need min_elevation < max_elevation")
        steps = 360.0 / self.horizontal_resolution_deg
        if self.horizontal_resolution_deg <= 0.0 or abs(steps - round(steps)) > 1e-6:
            raise SensorConfigError("horizontal_resolution_deg must divide 360 deg")
        if not 0.0 <= self.min_range_m < self.max_range_m:
            raise SensorConfigError("ranges must satisfy 0 <= min_range < max_range")
        if self.rate_hz <= 0.0:
            raise SensorConfigError(f"rate_hz must be > 0, got {self.rate_hz}")

    @property
    def horizontal_steps(self) -> int:
        return round(360.0 / self.horizontal_resolution_deg)

    @property
    def elevations_rad(self) -> FloatArray:
        return np.radians(
            np.linspace(self.min_elevation_deg, self.max_elevation_deg, self.channels)
        )

    @property
    def azimuths_rad(self) -> FloatArray:
        return np.arange(self.horizontal_steps, dtype=np.float64) * (
            2.0 * np.pi / self.horizontal_steps
        )


def beam_directions(config: LidarConfig) -> FloatArray:
    """Unit vectors (channels * horizontal_steps, 3) in the sensor frame, azimuth-major."""
    azimuth_grid, elevation_grid = np.meshgrid(
        config.azimuths_rad, config.elevations_rad, indexing="ij"
    )
    azimuth, elevation = azimuth_grid.ravel(), elevation_grid.ravel()
    return np.stack(
        [
            np.cos(elevation) * np.cos(azimuth),
            np.cos(elevation) * np.sin(azimuth),
            np.sin(elevation),
        ],
        axis=1,
    )


class LidarModel:
    def __init__(self, config: LidarConfig | None = None) -> None:
        self.config = config or LidarConfig()
        self._directions = beam_directions(self.config)
        self._mount_frame = MountFrame(self.config.mount)
        # The beams one axis per row: rotating them as (3, N) and gathering returned
        # components from contiguous rows are several times cheaper than on (N, 3).
        self._direction_axes = np.ascontiguousarray(self._directions.T)
        # The beams in the map frame for the last rotation seen (its bytes), with their
        # broad phase.
        self._fan: tuple[bytes, RayFan] | None = None

    @property
    def beam_count(self) -> int:
        return len(self._directions)

    def scan(
        self,
        vehicle_pose: Pose,
        boxes: ObstacleBoxes | None = None,
        exclude_index: int | None = None,
    ) -> npt.NDArray[np.float32]:
        """Points (M, 4) float32: x, y, z in the sensor frame (m), intensity.

        `exclude_index` names the box the sensor rides on, which it never sees.
        """
        config = self.config
        origin, sensor_to_map = self._mount_frame.in_map(vehicle_pose)
        boxes = boxes if boxes is not None else ObstacleBoxes.empty()
        if kernels.ACTIVE:
            fan = self._fan_for(sensor_to_map)
            return self._compiled_returns(origin, fan, boxes, exclude_index)
        directions = sensor_to_map @ self._direction_axes
        hits = cast_rays(origin, directions.T, boxes, config.max_range_m, exclude_index)
        returned = np.flatnonzero(
            (hits.distance >= config.min_range_m) & (hits.distance <= config.max_range_m)
        )
        distance = hits.distance[returned]
        points = np.empty((len(distance), 4), dtype=np.float32)
        for axis, components in enumerate(self._direction_axes):
            points[:, axis] = components[returned] * distance
        points[:, 3] = config.intensity.of(
            hits.surface[returned], hits.cos_incidence[returned], distance
        )
        return points

    def _fan_for(self, sensor_to_map: FloatArray) -> RayFan:
        """The beams turned by `sensor_to_map` into the map frame: kept, with what the
        box cast works out of them, until the rotation changes by a bit."""
        rotation = sensor_to_map.tobytes()
        if self._fan is None or self._fan[0] != rotation:
            self._fan = (rotation, RayFan(sensor_to_map @ self._direction_axes))
        return self._fan[1]

    def _compiled_returns(
        self,
        origin: FloatArray,
        fan: RayFan,
        boxes: ObstacleBoxes,
        exclude_index: int | None,
    ) -> npt.NDArray[np.float32]:
        """scan's points through the compiled pass (world/kernels/lidar_returns.py), bit
        for bit those of the numpy path."""
        config, intensity = self.config, self.config.intensity
        box_distance, box_cos = cast_fan(origin, fan, boxes, config.max_range_m, exclude_index)
        directions = fan.axes
        beams = self.beam_count
        points = np.empty((beams, 4), dtype=np.float32)
        lit, exponent = np.empty(beams), np.empty(beams)
        count = lidar_returns(
            float(origin[2]), directions, box_distance, box_cos, self._direction_axes,
            config.min_range_m, config.max_range_m,
            intensity.scale * intensity.ground_reflectivity,
            intensity.scale * intensity.object_reflectivity,
            -2.0 * intensity.extinction_per_m,
            points, lit, exponent,
        )  # fmt: skip
        extinction = exponent[:count]
        np.exp(extinction, out=extinction)
        lidar_intensities(points, lit, extinction)
        return points[:count]
