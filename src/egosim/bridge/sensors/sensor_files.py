"""/SaveSensorData: write the sensors' current frames to files.

file_dir comes from the network, so it resolves only inside the data roots (a
relative name is taken in each root; the directory must exist). Written:
`<name>.pcd` (the LiDAR cloud, PCD v0.7 binary, sensor frame), `<name>.json` (the
GPS fix and IMU reading, GPSMessage / sensor_msgs/Imu field names) and, for each
camera, `<name>_<frame_id>.jpg` or `.png` (its topic's format) or, for a depth
camera, `<name>_<frame_id>.tiff` (32-bit float metres, lossless). `<name>` is
custom_file_name when is_custom_file_name is true (a plain file name, no directories),
else `sensor_data_<sim time in µs>`.
"""

from __future__ import annotations

import json
import logging
from pathlib import Path
from typing import TYPE_CHECKING

from ...datapaths import PathOutsideRootsError, resolve_in_roots
from ...sensors import encode_pcd, gps_imu_snapshot
from ...sensors.camera import CameraMode
from ...sensors.image_encoding import ImageFormat, encode_depth_tiff, encode_image
from ..context import BridgeContext
from ..protocol.table import Row

if TYPE_CHECKING:
    from ...msgs.typed import morai_26_r1

log = logging.getLogger(__name__)


class SaveRequestError(Exception):
    """A SaveSensorData request that cannot be honoured; the message says why."""


def save_directory(file_dir: str, roots: tuple[Path, ...]) -> Path:
    try:
        directory = resolve_in_roots(file_dir or ".", roots)
    except (PathOutsideRootsError, OSError, ValueError) as error:
        # OSError: missing, or a name the system refuses (too long...); ValueError: NUL.
        raise SaveRequestError(f"file_dir {file_dir[:200]!r}: {error}") from error
    if not directory.is_dir():
        raise SaveRequestError(f"{file_dir!r} is not a directory")
    return directory


def target_path(path: Path, roots: tuple[Path, ...]) -> Path:
    """`path` itself, refused when an existing link there points out of the roots."""
    try:
        return resolve_in_roots(str(path), roots, must_exist=False)
    except (PathOutsideRootsError, OSError, ValueError) as error:
        raise SaveRequestError(str(error)) from error


def file_stem(context: BridgeContext, request: morai_26_r1.SaveSensorData) -> str:
    if not request.is_custom_file_name:
        return f"sensor_data_{round(context.world.sim_time * 1e6)}"
    name: str = request.custom_file_name
    if not name or name in (".", "..") or "/" in name or "\\" in name or "\x00" in name:
        raise SaveRequestError(f"custom_file_name {name!r} is not a plain file name")
    return name


def camera_files(context: BridgeContext, directory: Path, stem: str) -> dict[Path, bytes]:
    """Each camera's current frame as the file it is saved to."""
    if context.cameras is None or context.sensors is None:
        return {}
    rig, files = context.sensors, {}
    for k, camera in enumerate(rig.cameras):
        image = context.cameras.image(rig, context.world, k)
        name = f"{stem}_{rig.camera_frame_ids[k]}"
        if camera.config.mode is CameraMode.DEPTH:
            files[directory / f"{name}.tiff"] = encode_depth_tiff(image)  # type: ignore[arg-type]
            continue
        suffix = "jpg" if camera.format is ImageFormat.JPEG else "png"
        data = encode_image(image, camera.format, camera.config.jpeg_quality)  # type: ignore[arg-type]
        files[directory / f"{name}.{suffix}"] = data
    return files


def save_sensor_data(
    context: BridgeContext, request: morai_26_r1.SaveSensorData
) -> tuple[Path, ...]:
    """Write the PCD, JSON and camera files; their paths."""
    directory = save_directory(request.file_dir, context.data_roots)
    stem = file_stem(context, request)
    rig, world = context.sensors, context.world
    snapshot = gps_imu_snapshot(context.stamp(), rig.gps_fix(world), rig.imu_reading(world))
    cloud_path = target_path(directory / f"{stem}.pcd", context.data_roots)
    readings_path = target_path(directory / f"{stem}.json", context.data_roots)
    images = {
        target_path(path, context.data_roots): data
        for path, data in camera_files(context, directory, stem).items()
    }
    try:
        cloud_path.write_bytes(encode_pcd(rig.scan(world, context.objects())))
        readings_path.write_text(json.dumps(snapshot, indent=2), encoding="utf-8")
        for path, data in images.items():
            path.write_bytes(data)
    except OSError as error:
        raise SaveRequestError(f"cannot write {directory}: {error}") from error
    return (cloud_path, readings_path, *images)


def on_save_sensor_data(
    context: BridgeContext, row: Row, request: morai_26_r1.SaveSensorData
) -> None:
    try:
        paths = save_sensor_data(context, request)
    except SaveRequestError as error:
        log.error("%s: not saved: %s", row.name, error)
        return
    log.info("%s: wrote %s", row.name, ", ".join(str(path) for path in paths))
