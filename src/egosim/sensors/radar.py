"""Object-level automotive radar: one detection per object inside its field of view.

An object is detected at the centre of its box (footprint centre, half its height up)
when that point lies within [min_range, max_range] and inside the horizontal and
vertical fields of view, centred on the sensor's x axis. Per detection:

- position: the point in the sensor frame (x forward, y left, z up), m;
- azimuth: atan2(y, x) in the sensor frame, rad (positive to the left);
- range rate: the relative velocity along the line of sight, m/s (positive receding):
  (v_object - v_sensor) . p / |p| in the map frame, v_sensor including the ego's yaw
  rate times the mount's lever arm;
- amplitude: 10 log10 of the box's area seen along the line of sight, dB m²:
  height x (length |sin a| + width |cos a|), a the angle between the box's heading and
  the line of sight (a car seen head-on: width x height).

At most `max_detections`, nearest first (ties in table order). Gaussian noise on range,
azimuth and range rate is optional (std 0 by default).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field, replace

import numpy as np
import numpy.typing as npt

from egosim.sensors.errors import MissingRandomGeneratorError, SensorConfigError
from egosim.sensors.frames import MountFrame, MountPose
from egosim.sensors.vectors import add3, cross3, floats3
from egosim.world import kernels
from egosim.world.arrays import FloatArray
from egosim.world.kernels.radar_detections import (
    lines_of_sight,
    nearest_in_view,
    seen_areas,
    shown_centres,
)
from egosim.world.traffic.objects import ObjectTable
from egosim.world.vehicle import Pose

DEFAULT_RADAR_MOUNT = MountPose(x=3.7, z=0.2)
"""In the front bumper, m from the mount origin."""


@dataclass(frozen=True)
class RadarNoise:
    range_std_m: float = 0.0
    azimuth_std_rad: float = 0.0
    range_rate_std_m_s: float = 0.0

    def __post_init__(self) -> None:
        if min(self.range_std_m, self.azimuth_std_rad, self.range_rate_std_m_s) < 0.0:
            raise SensorConfigError("radar noise std values must be >= 0")

    @property
    def is_zero(self) -> bool:
        return self.range_std_m == self.azimuth_std_rad == self.range_rate_std_m_s == 0.0


@dataclass(frozen=True)
class RadarConfig:
    horizontal_fov_deg: float = 90.0
    vertical_fov_deg: float = 20.0
    min_range_m: float = 0.5
    max_range_m: float = 150.0
    max_detections: int = 64
    mount: MountPose = DEFAULT_RADAR_MOUNT
    noise: RadarNoise = field(default_factory=RadarNoise)

    def __post_init__(self) -> None:
        if not 0.0 < self.horizontal_fov_deg <= 360.0 or not 0.0 < self.vertical_fov_deg <= 180.0:
            raise SensorConfigError("radar fields of view must be in (0, 360] and (0, 180] deg")
        if not 0.0 <= self.min_range_m < self.max_range_m:
            raise SensorConfigError("radar ranges must satisfy 0 <= min_range < max_range")
        if not 0 <= self.max_detections <= 65535:
            raise SensorConfigError("max_detections must be 0..65535")


@dataclass(frozen=True, eq=False)
class RadarDetections:
    """Parallel arrays, nearest first: unique_ids (N,), positions (N, 3) sensor frame m,
    azimuths (N,) rad, range_rates (N,) m/s, amplitudes (N,) dB m²."""

    unique_ids: npt.NDArray[np.int64]
    positions: FloatArray
    azimuths: FloatArray
    range_rates: FloatArray
    amplitudes: FloatArray

    def __len__(self) -> int:
        return len(self.unique_ids)


@dataclass(frozen=True)
class RadarModel:
    config: RadarConfig = field(default_factory=RadarConfig)

    def detect(
        self,
        vehicle_pose: Pose,
        vehicle_velocity: tuple[float, float, float],
        yaw_rate: float,
        objects: ObjectTable,
        hidden_ids: tuple[int, ...] = (),
        rng: np.random.Generator | None = None,
    ) -> RadarDetections:
        """Detections of `objects` but `hidden_ids` (the carrier); `vehicle_velocity` is the
        carrier's velocity in the map frame (m/s), `yaw_rate` its yaw rate (rad/s)."""
        config = self.config
        if not config.noise.is_zero and rng is None:
            raise MissingRandomGeneratorError("a noisy radar needs a random generator")
        origin, sensor_to_map = self._mount_frame.in_map(vehicle_pose)
        lever = origin - np.array([vehicle_pose.x, vehicle_pose.y, vehicle_pose.z])
        sensor_velocity = np.array(
            add3(floats3(vehicle_velocity), cross3((0.0, 0.0, yaw_rate), lever.tolist()))
        )
        measure = self._compiled_detections if kernels.ACTIVE else self._detections
        detections, distance = measure(origin, sensor_to_map, sensor_velocity, objects, hidden_ids)
        if config.noise.is_zero:
            return detections
        assert rng is not None
        return self._noisy(detections, distance, rng)

    def _detections(
        self,
        origin: FloatArray,
        sensor_to_map: FloatArray,
        sensor_velocity: FloatArray,
        objects: ObjectTable,
        hidden_ids: tuple[int, ...],
    ) -> tuple[RadarDetections, FloatArray]:
        """The noiseless detections, and their distances (m)."""
        config = self.config
        # A comparison per hidden id (one, the carrier): np.isin costs ten times more.
        keep = np.ones(len(objects), dtype=bool)
        for hidden in hidden_ids:
            keep &= objects.unique_ids != hidden
        centres = objects.positions[keep] + np.column_stack(
            (np.zeros((int(keep.sum()), 2)), objects.sizes[keep, 2] / 2.0)
        )
        local = (centres - origin) @ sensor_to_map
        distance = np.linalg.norm(local, axis=1)
        azimuth = np.arctan2(local[:, 1], local[:, 0])
        elevation = np.arctan2(local[:, 2], np.hypot(local[:, 0], local[:, 1]))
        inside = (
            (distance >= config.min_range_m)
            & (distance <= config.max_range_m)
            & (np.abs(azimuth) <= self._half_azimuth)
            & (np.abs(elevation) <= self._half_elevation)
        )
        order = np.flatnonzero(inside)
        order = order[np.argsort(distance[order], kind="stable")][: config.max_detections]

        line_of_sight = (centres[order] - origin) / distance[order, None]
        velocities = objects.velocities[keep][order]
        range_rate = np.einsum("ij,ij->i", velocities - sensor_velocity, line_of_sight)

        sizes = objects.sizes[keep][order]
        sight_heading = np.arctan2(line_of_sight[:, 1], line_of_sight[:, 0])
        angle = objects.headings[keep][order] - sight_heading
        area = sizes[:, 2] * (
            sizes[:, 0] * np.abs(np.sin(angle)) + sizes[:, 1] * np.abs(np.cos(angle))
        )
        detections = RadarDetections(
            unique_ids=objects.unique_ids[keep][order],
            positions=local[order],
            azimuths=azimuth[order],
            range_rates=range_rate,
            amplitudes=10.0 * np.log10(np.maximum(area, 1e-6)),
        )
        return detections, distance[order]

    def _compiled_detections(
        self,
        origin: FloatArray,
        sensor_to_map: FloatArray,
        sensor_velocity: FloatArray,
        objects: ObjectTable,
        hidden_ids: tuple[int, ...],
    ) -> tuple[RadarDetections, FloatArray]:
        """_detections through the compiled passes (world/kernels/radar_detections.py),
        bit for bit: every call that stays numpy's is made on arrays of the same values
        and layout."""
        config = self.config
        shown = np.empty(len(objects), dtype=np.intp)
        from_origin = np.empty((len(objects), 3))
        count = shown_centres(
            objects.unique_ids, np.array(hidden_ids, dtype=np.int64), objects.positions,
            objects.sizes, origin, shown, from_origin,
        )  # fmt: skip
        shown, from_origin = shown[:count], from_origin[:count]
        local = from_origin @ sensor_to_map
        azimuth = np.arctan2(local[:, 1], local[:, 0])
        elevation = np.arctan2(local[:, 2], np.hypot(local[:, 0], local[:, 1]))
        distance = np.empty(count)
        order = nearest_in_view(
            local, azimuth, elevation, config.min_range_m, config.max_range_m,
            self._half_azimuth, self._half_elevation, config.max_detections, distance,
        )  # fmt: skip
        sight, relative_velocity = np.empty((len(order), 3)), np.empty((len(order), 3))
        if not lines_of_sight(
            order, shown, from_origin, distance, objects.velocities, sensor_velocity,
            sight, relative_velocity,
        ):  # fmt: skip
            return self._detections(origin, sensor_to_map, sensor_velocity, objects, hidden_ids)
        range_rate = np.einsum("ij,ij->i", relative_velocity, sight)
        detected = shown[order]
        area = np.empty(len(order))
        sight_heading = np.arctan2(sight[:, 1], sight[:, 0])
        seen_areas(detected, objects.headings, objects.sizes, sight_heading, area)
        detections = RadarDetections(
            unique_ids=objects.unique_ids[detected],
            positions=local[order],
            azimuths=azimuth[order],
            range_rates=range_rate,
            amplitudes=10.0 * np.log10(area),
        )
        return detections, distance[order]

    @functools.cached_property
    def _mount_frame(self) -> MountFrame:
        return MountFrame(self.config.mount)

    @functools.cached_property
    def _half_azimuth(self) -> float:
        return math.radians(self.config.horizontal_fov_deg) / 2.0

    @functools.cached_property
    def _half_elevation(self) -> float:
        return math.radians(self.config.vertical_fov_deg) / 2.0

    def _noisy(
        self, detections: RadarDetections, distance: FloatArray, rng: np.random.Generator
    ) -> RadarDetections:
        """`detections` (at `distance`, m) with the configured range, azimuth and range
        rate noise."""
        noise = self.config.noise
        count = len(detections)
        positions = detections.positions
        scale = 1.0 + rng.normal(0.0, noise.range_std_m, count) / distance
        turn = rng.normal(0.0, noise.azimuth_std_rad, count)
        cos, sin = np.cos(turn), np.sin(turn)
        x, y = positions[:, 0].copy(), positions[:, 1].copy()
        positions = np.column_stack((cos * x - sin * y, sin * x + cos * y, positions[:, 2]))
        positions = positions * scale[:, None]
        return replace(
            detections,
            positions=positions,
            azimuths=np.arctan2(positions[:, 1], positions[:, 0]),
            range_rates=detections.range_rates + rng.normal(0.0, noise.range_rate_std_m_s, count),
        )
