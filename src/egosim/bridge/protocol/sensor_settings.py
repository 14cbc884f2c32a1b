"""The `sensors:` section of the network settings file: mounts, noise and LiDAR geometry.

Topic names, rates and on/off of the sensor rows come from the `rows:` section like
every other row; this section holds what MORAI's sensor edit dialog holds:

sensors:
  seed: 0                        # noise generator seed (one stream per sensor)
  gps:
    frame_id: gps
    mount: {x: 0.0, y: 0.0, z: 1.5, roll_deg: 0, pitch_deg: 0, yaw_deg: 0}
    noise: {horizontal_std_m: 0.0, vertical_std_m: 0.0}
  imu:
    mount: {...}
    noise: {orientation_std_rad: 0.0, angular_velocity_std_rad_s: 0.0,
            linear_acceleration_std_m_s2: 0.0,
            angular_velocity_bias_rad_s: [0, 0, 0], linear_acceleration_bias_m_s2: [0, 0, 0]}
  lidar:
    mount: {x: 0.0, y: 0.0, z: 1.8}
    channels: 16
    min_elevation_deg: -15
    max_elevation_deg: 15
    horizontal_resolution_deg: 0.2
    min_range_m: 0.5
    max_range_m: 100
  cameras:                       # a list; absent: one default front camera; []: none
    - frame_id: Camera           # default Camera, or Camera-1, Camera-2... on a shared topic
      topic: /image_jpeg/compressed   # default: the camera row's topic (depth: /image)
      mode: rgb                  # rgb | semantic | instance | depth
      width: 640
      height: 480
      fov_deg: 90
      fov_axis: vertical         # vertical (MORAI, Unity) | horizontal
      rate_hz: 30                # default: the camera row's rate
      format: jpeg               # jpeg | png; default jpeg for rgb, png for labels
      jpeg_quality: 90
      mount: {x: 1.5, y: 0.0, z: 1.2, roll_deg: 0, pitch_deg: 0, yaw_deg: 0}
  radar:
    frame_id: radar
    mount: {x: 3.7, z: 0.2}
    horizontal_fov_deg: 90
    vertical_fov_deg: 20
    min_range_m: 0.5
    max_range_m: 150
    max_detections: 64
    noise: {range_std_m: 0, azimuth_std_rad: 0, range_rate_std_m_s: 0}

Mounts (x, y, z, roll, pitch, yaw) are MORAI's: from the midpoint of the rear axle at
wheel-centre height (see egosim.world.vehicle.mount_origin).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field, fields, replace
from enum import Enum
from typing import TypeVar, overload

from ...json_value import JsonObject, JsonValue
from ...sensors import GpsNoise, ImuNoise, LidarConfig, MountPose, SensorConfigError
from ...sensors.camera import CameraConfig, CameraMode, FovAxis
from ...sensors.image_encoding import ImageFormat
from ...sensors.radar import RadarConfig, RadarNoise
from ...sensors.vectors import Vector3Tuple
from ...yamltext import Problems, YamlDocument, YamlFileError
from .table import DEPTH_TOPIC
from .units import rad

T = TypeVar("T")
D = TypeVar("D")
PointSettings = TypeVar("PointSettings", "GpsSettings", "ImuSettings")
NoiseModel = TypeVar("NoiseModel", GpsNoise, ImuNoise, RadarNoise)
E = TypeVar("E", bound=Enum)

SENSOR_KINDS = ("gps", "imu", "lidar")
"""Also the sensor indices of SensorPosControl: 0 GPS, 1 IMU, 2 LiDAR; the cameras follow
(3, 4, ... in the order of `cameras:`), then the radar."""
SECTION_KEYS = ("seed", *SENSOR_KINDS, "cameras", "radar")
CAMERA_NUMBERS = ("width", "height", "fov_deg", "rate_hz", "jpeg_quality")
RADAR_NUMBERS = (
    "horizontal_fov_deg",
    "vertical_fov_deg",
    "min_range_m",
    "max_range_m",
    "max_detections",
)

MOUNT_FIELDS = {
    "x": "x",
    "y": "y",
    "z": "z",
    "roll_deg": "roll",
    "pitch_deg": "pitch",
    "yaw_deg": "yaw",
}
LIDAR_FIELDS = (
    "channels",
    "min_elevation_deg",
    "max_elevation_deg",
    "horizontal_resolution_deg",
    "min_range_m",
    "max_range_m",
)
# The range of every numeric setting (inclusive; docs/sensors_and_time.md lists them):
# wide enough for any real sensor, narrow enough that no setting can make the simulator
# allocate or compute without bound.
RANGES: dict[str, tuple[float, float]] = {
    "seed": (0, 2**32 - 1),
    "x": (-100.0, 100.0),
    "y": (-100.0, 100.0),
    "z": (-100.0, 100.0),
    "roll_deg": (-360.0, 360.0),
    "pitch_deg": (-360.0, 360.0),
    "yaw_deg": (-360.0, 360.0),
    "channels": (1, 256),
    "min_elevation_deg": (-90.0, 90.0),
    "max_elevation_deg": (-90.0, 90.0),
    "horizontal_resolution_deg": (0.05, 360.0),
    "min_range_m": (0.0, 1000.0),
    "max_range_m": (0.01, 1000.0),
    "horizontal_std_m": (0.0, 1000.0),
    "vertical_std_m": (0.0, 1000.0),
    "orientation_std_rad": (0.0, 10.0),
    "angular_velocity_std_rad_s": (0.0, 100.0),
    "linear_acceleration_std_m_s2": (0.0, 1000.0),
    "angular_velocity_bias_rad_s": (-100.0, 100.0),
    "linear_acceleration_bias_m_s2": (-1000.0, 1000.0),
    "width": (1, 8192),
    "height": (1, 8192),
    "fov_deg": (0.01, 179.99),
    "rate_hz": (0.1, 1000.0),
    "jpeg_quality": (1, 100),
    "horizontal_fov_deg": (0.01, 360.0),
    "vertical_fov_deg": (0.01, 180.0),
    "max_detections": (0, 65535),
    "range_std_m": (0.0, 100.0),
    "azimuth_std_rad": (0.0, 3.2),
    "range_rate_std_m_s": (0.0, 100.0),
}
#: A LiDAR scan casts channels x 360 / horizontal_resolution_deg rays.
MAX_LIDAR_RAYS = 1_000_000
DEFAULT_GPS_MOUNT = MountPose(z=1.5)
DEFAULT_IMU_MOUNT = MountPose()


@dataclass(frozen=True)
class GpsSettings:
    frame_id: str = "gps"
    mount: MountPose = DEFAULT_GPS_MOUNT
    noise: GpsNoise = field(default_factory=GpsNoise)


@dataclass(frozen=True)
class ImuSettings:
    frame_id: str = "imu"
    mount: MountPose = DEFAULT_IMU_MOUNT
    noise: ImuNoise = field(default_factory=ImuNoise)


@dataclass(frozen=True)
class LidarSettings:
    frame_id: str = "lidar"
    config: LidarConfig = field(default_factory=LidarConfig)


@dataclass(frozen=True)
class CameraSettings:
    """One camera. topic and rate None: the camera row's (depth: DEPTH_TOPIC); frame_id
    None: `Camera`, or `Camera-<n>` when several cameras share the topic."""

    config: CameraConfig = field(default_factory=CameraConfig)
    frame_id: str | None = None
    topic: str | None = None
    rate_hz: float | None = None
    image_format: ImageFormat | None = None

    @property
    def format(self) -> ImageFormat:
        if self.image_format is not None:
            return self.image_format
        return ImageFormat.JPEG if self.config.mode is CameraMode.RGB else ImageFormat.PNG


def camera_topic(camera: CameraSettings, row_topic: str) -> str:
    """Where a camera publishes: its own topic, else the camera row's (depth: /image)."""
    if camera.topic is not None:
        return camera.topic
    return DEPTH_TOPIC if camera.config.mode is CameraMode.DEPTH else row_topic


@dataclass(frozen=True)
class RadarSettings:
    frame_id: str = "radar"
    config: RadarConfig = field(default_factory=RadarConfig)


@dataclass(frozen=True)
class SensorSettings:
    seed: int = 0
    gps: GpsSettings = field(default_factory=GpsSettings)
    imu: ImuSettings = field(default_factory=ImuSettings)
    lidar: LidarSettings = field(default_factory=LidarSettings)
    cameras: tuple[CameraSettings, ...] = (CameraSettings(),)
    radar: RadarSettings = field(default_factory=RadarSettings)


Path = tuple[str, ...]


def parse_sensor_settings(document: YamlDocument, data: JsonValue) -> SensorSettings:
    """The `sensors:` mapping of a network settings document; errors name file, line and
    field, every problem of the section at once."""
    path: Path = ("sensors",)
    if data is None:
        return SensorSettings()
    problems = Problems()
    with problems.collecting():
        _check_keys(document, path, data, SECTION_KEYS)
    if not isinstance(data, dict):
        problems.raise_any()
        return SensorSettings()  # not reached: a section that is no mapping is a problem
    seed = data.get("seed", 0)
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        problems.add(document.error((*path, "seed"), "expected a non-negative integer"))
    else:
        with problems.collecting():
            _number(document, (*path, "seed"), seed, integer=True)
    settings = SensorSettings(seed=seed if isinstance(seed, int) else 0)
    with problems.collecting():
        gps = _point_sensor(document, (*path, "gps"), data.get("gps"), GpsSettings)
        settings = replace(settings, gps=gps)
    with problems.collecting():
        imu = _point_sensor(document, (*path, "imu"), data.get("imu"), ImuSettings)
        settings = replace(settings, imu=imu)
    with problems.collecting():
        settings = replace(settings, lidar=_lidar(document, (*path, "lidar"), data.get("lidar")))
    with problems.collecting():
        settings = replace(settings, cameras=_cameras(document, (*path, "cameras"), data))
    with problems.collecting():
        settings = replace(settings, radar=_radar(document, (*path, "radar"), data.get("radar")))
    problems.raise_any()
    return settings


def _cameras(document: YamlDocument, path: Path, section: JsonObject) -> tuple[CameraSettings, ...]:
    if "cameras" not in section:
        return SensorSettings().cameras
    data = section["cameras"]
    if data is None:
        return ()
    if not isinstance(data, list):
        raise document.error(path, "expected a list of cameras")
    return tuple(_camera(document, (*path, str(k)), item) for k, item in enumerate(data))


def _camera(document: YamlDocument, path: Path, item: JsonValue) -> CameraSettings:
    if item is None:
        return CameraSettings()
    known = ("frame_id", "topic", "mode", "fov_axis", "format", "mount", *CAMERA_NUMBERS)
    data = _check_keys(document, path, item, known)
    read = _Fields(document, path, data)
    defaults = CameraConfig()
    width = read.integer("width", defaults.width)
    height = read.integer("height", defaults.height)
    fov_deg = read.number("fov_deg", defaults.fov_deg)
    rate = read.number("rate_hz", None)
    jpeg_quality = read.integer("jpeg_quality", defaults.jpeg_quality)
    mode = _choice(document, (*path, "mode"), data.get("mode", "rgb"), CameraMode)
    fov_axis = _choice(document, (*path, "fov_axis"), data.get("fov_axis", "vertical"), FovAxis)
    mount = _mount(document, (*path, "mount"), data.get("mount"), defaults.mount)
    config = _built(
        document,
        path,
        lambda: replace(
            defaults,
            width=width,
            height=height,
            fov_deg=fov_deg,
            rate_hz=defaults.rate_hz if rate is None else rate,
            jpeg_quality=jpeg_quality,
            mode=mode,
            fov_axis=fov_axis,
            mount=mount,
        ),
    )
    image_format = None
    if "format" in data:
        image_format = _choice(document, (*path, "format"), data["format"], ImageFormat)
        if config.mode is CameraMode.DEPTH:
            raise document.error((*path, "format"), "a depth camera sends raw 32FC1 images")
    topic = data.get("topic")
    if topic is not None and (not isinstance(topic, str) or not topic.startswith("/")):
        raise document.error((*path, "topic"), f"expected a topic name like /camera, got {topic!r}")
    frame_id = _frame_id(document, path, data, "Camera") if "frame_id" in data else None
    return CameraSettings(config, frame_id, topic, rate, image_format)


def _radar(document: YamlDocument, path: Path, section: JsonValue) -> RadarSettings:
    defaults = RadarSettings()
    if section is None:
        return defaults
    data = _check_keys(document, path, section, ("frame_id", "mount", "noise", *RADAR_NUMBERS))
    read = _Fields(document, path, data)
    default = defaults.config
    horizontal_fov_deg = read.number("horizontal_fov_deg", default.horizontal_fov_deg)
    vertical_fov_deg = read.number("vertical_fov_deg", default.vertical_fov_deg)
    min_range_m = read.number("min_range_m", default.min_range_m)
    max_range_m = read.number("max_range_m", default.max_range_m)
    max_detections = read.integer("max_detections", default.max_detections)
    mount = _mount(document, (*path, "mount"), data.get("mount"), default.mount)
    noise = _noise(document, (*path, "noise"), data.get("noise"), default.noise)
    config = _built(
        document,
        path,
        lambda: replace(
            default,
            horizontal_fov_deg=horizontal_fov_deg,
            vertical_fov_deg=vertical_fov_deg,
            min_range_m=min_range_m,
            max_range_m=max_range_m,
            max_detections=max_detections,
            mount=mount,
            noise=noise,
        ),
    )
    return RadarSettings(frame_id=_frame_id(document, path, data, defaults.frame_id), config=config)


def _choice(document: YamlDocument, path: Path, value: JsonValue, kind: type[E]) -> E:
    for member in kind:
        if value == member.value:
            return member
    known = ", ".join(str(m.value) for m in kind)
    raise document.error(path, f"expected one of {known}, got {value!r}")


def _point_sensor(
    document: YamlDocument,
    path: Path,
    section: JsonValue,
    settings: type[PointSettings],
) -> PointSettings:
    """GPS or IMU settings: a frame id, a mount and a noise model, each defaulted."""
    defaults = settings()
    if section is None:
        return defaults
    data = _check_keys(document, path, section, ("frame_id", "mount", "noise"))
    problems = Problems()
    frame_id, mount, model = defaults.frame_id, defaults.mount, defaults.noise
    with problems.collecting():
        frame_id = _frame_id(document, path, data, defaults.frame_id)
    with problems.collecting():
        mount = _mount(document, (*path, "mount"), data.get("mount"), defaults.mount)
    with problems.collecting():
        model = _noise(document, (*path, "noise"), data.get("noise"), defaults.noise)
    problems.raise_any()
    return replace(defaults, frame_id=frame_id, mount=mount, noise=model)


def _lidar(document: YamlDocument, path: Path, section: JsonValue) -> LidarSettings:
    defaults = LidarSettings()
    if section is None:
        return defaults
    data = _check_keys(document, path, section, ("frame_id", "mount", *LIDAR_FIELDS))
    problems = Problems()
    default = defaults.config
    resolution = data.get("horizontal_resolution_deg")
    not_positive = (
        isinstance(resolution, int | float) and not isinstance(resolution, bool) and resolution <= 0
    )
    if not_positive:
        problems.add(document.error((*path, "horizontal_resolution_deg"), "must be > 0 deg"))
    read = _Fields(document, path, data, problems)
    channels = read.integer("channels", default.channels)
    min_elevation_deg = read.number("min_elevation_deg", default.min_elevation_deg)
    max_elevation_deg = read.number("max_elevation_deg", default.max_elevation_deg)
    horizontal_resolution_deg = (
        default.horizontal_resolution_deg
        if not_positive
        else read.number("horizontal_resolution_deg", default.horizontal_resolution_deg)
    )
    min_range_m = read.number("min_range_m", default.min_range_m)
    max_range_m = read.number("max_range_m", default.max_range_m)
    rays = channels * 360.0 / horizontal_resolution_deg
    if not problems.found and rays > MAX_LIDAR_RAYS:
        problems.add(
            document.error(
                path,
                f"channels x 360 / horizontal_resolution_deg is "
                f"{rays:.0f} rays a scan (at most {MAX_LIDAR_RAYS})",
            )
        )
    mount = default.mount
    with problems.collecting():
        mount = _mount(document, (*path, "mount"), data.get("mount"), mount)
    frame_id = defaults.frame_id
    with problems.collecting():
        frame_id = _frame_id(document, path, data, frame_id)
    problems.raise_any()
    config = _built(
        document,
        path,
        lambda: replace(
            default,
            channels=channels,
            min_elevation_deg=min_elevation_deg,
            max_elevation_deg=max_elevation_deg,
            horizontal_resolution_deg=horizontal_resolution_deg,
            min_range_m=min_range_m,
            max_range_m=max_range_m,
            mount=mount,
        ),
    )
    return LidarSettings(frame_id=frame_id, config=config)


def _mount(document: YamlDocument, path: Path, section: JsonValue, default: MountPose) -> MountPose:
    if section is None:
        return default
    data = _check_keys(document, path, section, tuple(MOUNT_FIELDS))
    problems = Problems()
    values = {}
    for key, attribute in MOUNT_FIELDS.items():
        if key in data:
            with problems.collecting():
                value = _number(document, (*path, key), data[key])
                values[attribute] = rad(value) if key.endswith("_deg") else value
    problems.raise_any()
    return replace(default, **values)


def _noise(
    document: YamlDocument, path: Path, section: JsonValue, default: NoiseModel
) -> NoiseModel:
    """A noise model from its own field names (std values, bias vectors); a field left
    out keeps `default`'s value."""
    if section is None:
        return default
    data = _check_keys(document, path, section, tuple(f.name for f in fields(default)))
    problems = Problems()
    build = _noise_builder(_Fields(document, path, data, problems), default)
    problems.raise_any()
    return _built(document, path, build)


@overload
def _noise_builder(read: _Fields, default: GpsNoise) -> Callable[[], GpsNoise]: ...
@overload
def _noise_builder(read: _Fields, default: ImuNoise) -> Callable[[], ImuNoise]: ...
@overload
def _noise_builder(read: _Fields, default: RadarNoise) -> Callable[[], RadarNoise]: ...
def _noise_builder(
    read: _Fields, default: GpsNoise | ImuNoise | RadarNoise
) -> Callable[[], GpsNoise] | Callable[[], ImuNoise] | Callable[[], RadarNoise]:
    """What builds the noise model whose fields `read` reads (the model checks them)."""
    if isinstance(default, GpsNoise):
        horizontal_std_m = read.number("horizontal_std_m", default.horizontal_std_m)
        vertical_std_m = read.number("vertical_std_m", default.vertical_std_m)
        return lambda: replace(
            default, horizontal_std_m=horizontal_std_m, vertical_std_m=vertical_std_m
        )
    if isinstance(default, ImuNoise):
        orientation_std_rad = read.number("orientation_std_rad", default.orientation_std_rad)
        angular_velocity_std_rad_s = read.number(
            "angular_velocity_std_rad_s", default.angular_velocity_std_rad_s
        )
        linear_acceleration_std_m_s2 = read.number(
            "linear_acceleration_std_m_s2", default.linear_acceleration_std_m_s2
        )
        angular_velocity_bias_rad_s = read.vector(
            "angular_velocity_bias_rad_s", default.angular_velocity_bias_rad_s
        )
        linear_acceleration_bias_m_s2 = read.vector(
            "linear_acceleration_bias_m_s2", default.linear_acceleration_bias_m_s2
        )
        return lambda: replace(
            default,
            orientation_std_rad=orientation_std_rad,
            angular_velocity_std_rad_s=angular_velocity_std_rad_s,
            linear_acceleration_std_m_s2=linear_acceleration_std_m_s2,
            angular_velocity_bias_rad_s=angular_velocity_bias_rad_s,
            linear_acceleration_bias_m_s2=linear_acceleration_bias_m_s2,
        )
    range_std_m = read.number("range_std_m", default.range_std_m)
    azimuth_std_rad = read.number("azimuth_std_rad", default.azimuth_std_rad)
    range_rate_std_m_s = read.number("range_rate_std_m_s", default.range_rate_std_m_s)
    return lambda: replace(
        default,
        range_std_m=range_std_m,
        azimuth_std_rad=azimuth_std_rad,
        range_rate_std_m_s=range_rate_std_m_s,
    )


@dataclass(frozen=True)
class _Fields:
    """The fields of one checked mapping, each read within its range or else its default.

    Without `problems` a wrong field raises; with them it is reported there and reads as
    its default, so that every problem of the mapping is found at once."""

    document: YamlDocument
    path: Path
    data: JsonObject
    problems: Problems | None = None

    def number(self, name: str, default: D) -> float | D:
        return self._read(name, default, lambda path, value: _number(self.document, path, value))

    def integer(self, name: str, default: D) -> int | D:
        return self._read(name, default, lambda path, value: _integer(self.document, path, value))

    def vector(self, name: str, default: D) -> Vector3Tuple | D:
        bounds = RANGES[name]
        return self._read(
            name, default, lambda path, value: _vector(self.document, path, value, bounds)
        )

    def _read(self, name: str, default: D, read: Callable[[Path, JsonValue], T]) -> T | D:
        if name not in self.data:
            return default
        if self.problems is None:
            return read((*self.path, name), self.data[name])
        with self.problems.collecting():
            return read((*self.path, name), self.data[name])
        return default


def _frame_id(document: YamlDocument, path: Path, data: JsonObject, default: str) -> str:
    frame_id = data.get("frame_id", default)
    if not isinstance(frame_id, str) or not frame_id or "/" in frame_id.strip("/"):
        raise document.error((*path, "frame_id"), f"not a tf frame name: {frame_id!r}")
    return frame_id


def _check_keys(
    document: YamlDocument, path: Path, data: JsonValue, known: tuple[str, ...]
) -> JsonObject:
    """`data` as a mapping of known keys only; every unknown key is reported."""
    if not isinstance(data, dict):
        raise document.error(path, f"expected a mapping ({', '.join(known)})")
    unknown = [
        document.error((*path, str(key)), f"unknown field (known: {', '.join(known)})")
        for key in data
        if key not in known
    ]
    if unknown:
        raise YamlFileError.of_all(unknown)
    return data


def _number(
    document: YamlDocument,
    path: Path,
    value: JsonValue,
    integer: bool = False,
    bounds: tuple[float, float] | None = None,
) -> float:
    """A finite number within `bounds` (default: the range of the field `path` ends in)."""
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise document.error(path, "expected a number")
    if not math.isfinite(value):
        raise document.error(path, "expected a finite number")
    if integer and not isinstance(value, int):
        raise document.error(path, "expected an integer")
    low, high = bounds or RANGES[path[-1]]
    if value < low:
        raise document.error(path, f"must be >= {low:g} (range {low:g}..{high:g}), got {value}")
    if value > high:
        raise document.error(path, f"must be <= {high:g} (range {low:g}..{high:g}), got {value}")
    return value


def _integer(document: YamlDocument, path: Path, value: JsonValue) -> int:
    """An integer within the range of the field `path` ends in."""
    return int(_number(document, path, value, integer=True))


def _vector(
    document: YamlDocument, path: Path, value: JsonValue, bounds: tuple[float, float]
) -> Vector3Tuple:
    if not isinstance(value, list) or len(value) != 3:
        raise document.error(path, "expected a list of 3 numbers (x, y, z)")
    x, y, z = (
        float(_number(document, (*path, str(k)), v, bounds=bounds)) for k, v in enumerate(value)
    )
    return x, y, z


def _built(document: YamlDocument, path: Path, build: Callable[[], T]) -> T:
    """The sensor models check their own parameters; their errors point at `path`."""
    try:
        return build()
    except SensorConfigError as error:
        raise document.error(path, str(error)) from None
