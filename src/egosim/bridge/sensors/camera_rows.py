"""Camera topics: images (CompressedImage JPEG/PNG, or 32FC1 depth Image) and CameraInfo.

The `camera` row of the table gives the default topic, rate and on/off; every camera of
the `sensors:` section publishes on its own topic or on the row's (a depth camera on
MORAI's /image). Cameras sharing a topic publish together, one message each, told apart
by header.frame_id (`Camera-1`, `Camera-2`, ...), at the rate of the first of them
(its rate_hz, else the row's). Beside each image topic, sensor_msgs/CameraInfo in the
same namespace: /image_jpeg/camera_info for /image_jpeg/compressed, /camera_info for
/image.

A camera renders only when its image topic has a subscriber or a recording tap, because
a row is only built then. While synchronous mode holds time, the cameras render only for
a tick a SyncModeCtrlCmd asked to capture (sensor_capture), whatever their rate.
"""

from __future__ import annotations

import logging
import posixpath
from collections.abc import Callable
from dataclasses import replace
from typing import TYPE_CHECKING, Final

import numpy as np

from ...sensors.camera import CameraMode
from ...sensors.image_encoding import depth_bytes
from ..context import BridgeContext
from ..protocol.network import NetworkSettings
from ..protocol.sensor_settings import camera_topic
from ..protocol.table import Row
from ..rate_schedule import RateSchedule
from .sensor_rig import optical_frame

if TYPE_CHECKING:
    from ...msgs.typed import standard
    from ..core import Bridge, Builder

log = logging.getLogger(__name__)

COMPRESSED_IMAGE: Final = "sensor_msgs/CompressedImage"
RAW_IMAGE: Final = "sensor_msgs/Image"
CAMERA_INFO: Final = "sensor_msgs/CameraInfo"


def camera_info_topic(image_topic: str) -> str:
    """The CameraInfo topic beside an image topic: `camera_info` in the same namespace."""
    return posixpath.join(posixpath.dirname(image_topic), "camera_info")


def camera_topic_names(settings: NetworkSettings) -> list[str]:
    """Every topic the configured cameras publish: images and their CameraInfo."""
    row = settings.row("camera")
    if not row.enabled:
        return []
    names: list[str] = []
    for camera in settings.sensors.cameras:
        topic = camera_topic(camera, row.name)
        names += [n for n in (topic, camera_info_topic(topic)) if n not in names]
    return names


def open_camera_rows(bridge: Bridge, row: Row) -> Callable[[], None]:
    """Advertise every camera's image topic and its CameraInfo (the `camera` row's opener);
    returns what withdraws them all."""
    context: BridgeContext = bridge.context
    withdrawers: list[Callable[[], None]] = []

    def withdraw() -> None:
        for withdraw_topic in withdrawers:
            withdraw_topic()

    if context.cameras is None:
        return withdraw
    rig = context.sensors
    topics: dict[str, list[int]] = {}
    # From the row in force: the network settings may rename it while the run goes on.
    for k, camera in enumerate(rig.cameras):
        topics.setdefault(camera_topic(camera, row.name), []).append(k)
    for topic, sharing in topics.items():
        first = rig.cameras[sharing[0]]
        rate = first.rate_hz if first.rate_hz is not None else row.rate_hz
        depth = first.config.mode is CameraMode.DEPTH
        mixed = [k for k in sharing if (rig.cameras[k].config.mode is CameraMode.DEPTH) != depth]
        cameras = tuple(k for k in sharing if k not in mixed)
        if mixed:
            log.error(
                "%s: depth and colour cameras cannot share a topic; cameras %s are off",
                topic,
                ", ".join(rig.camera_frame_ids[k] for k in mixed),
            )
        # Built every tick, due by its own schedule: sync mode's captures are off period.
        schedule = CameraSchedule(rate)
        image_row = replace(
            row,
            key=f"camera {topic}",
            name=topic,
            type_name=RAW_IMAGE if depth else COMPRESSED_IMAGE,
            rate_hz=None,
        )
        info_row = replace(
            image_row,
            key=f"camera_info {topic}",
            name=camera_info_topic(topic),
            type_name=CAMERA_INFO,
        )
        withdrawers.append(bridge.advertise(image_row, _image_builder(cameras, schedule)))
        withdrawers.append(bridge.advertise(info_row, _info_builder(cameras, schedule)))
    return withdraw


class CameraSchedule:
    """When a topic's cameras publish: at their rate in loop time, or, while sync mode
    holds time, on the ticks a client captures. The image and its CameraInfo ask in the
    same tick, so both go out together."""

    def __init__(self, rate_hz: float | None) -> None:
        self._rate = RateSchedule(rate_hz)
        self._decided: tuple[float, bool] | None = None

    def due(self, context: BridgeContext) -> bool:
        now = context.pipeline.loop_time
        if self._decided is not None and self._decided[0] == now:
            return self._decided[1]
        due = context.sync.capture_cameras if context.sync.holds_time else self._rate.take(now)
        self._decided = (now, due)
        return due


def _image_builder(cameras: tuple[int, ...], schedule: CameraSchedule) -> Builder:
    def build(
        context: BridgeContext, row: Row
    ) -> list[standard.CompressedImage | standard.Image] | None:
        if not schedule.due(context):
            return None
        return [camera_image_message(context, k) for k in cameras]

    return build


def _info_builder(cameras: tuple[int, ...], schedule: CameraSchedule) -> Builder:
    def build(context: BridgeContext, row: Row) -> list[standard.CameraInfo] | None:
        if not schedule.due(context):
            return None
        return [camera_info_message(context, k) for k in cameras]

    return build


def camera_image_message(
    context: BridgeContext, k: int
) -> standard.CompressedImage | standard.Image:
    """Camera k's current image as the message its topic carries."""
    assert context.cameras is not None and context.sensors is not None
    rig = context.sensors
    camera = rig.cameras[k]
    header = context.header(rig.camera_frame_ids[k])
    profile = context.profile
    if camera.config.mode is CameraMode.DEPTH:
        image = context.cameras.image(rig, context.world, k)
        height, width = image.shape
        return profile.message(RAW_IMAGE).new(
            header=header,
            height=height,
            width=width,
            encoding="32FC1",
            is_bigendian=0,
            step=4 * width,
            data=np.frombuffer(depth_bytes(image), dtype=np.uint8),  # type: ignore[arg-type]
        )
    data = context.cameras.encoded_image(rig, context.world, k)
    return profile.message(COMPRESSED_IMAGE).new(
        header=header, format=camera.format.value, data=np.frombuffer(data, dtype=np.uint8)
    )


def camera_info_message(context: BridgeContext, k: int) -> standard.CameraInfo:
    """sensor_msgs/CameraInfo of camera k: no distortion, K and P from its intrinsics.

    Its frame is the camera's REP 103 optical frame (`<frame_id>_optical` on /tf), the
    frame K projects from."""
    assert context.sensors is not None
    rig = context.sensors
    intrinsics = rig.cameras[k].config.intrinsics()
    k_matrix = intrinsics.matrix
    projection = np.zeros((3, 4))
    projection[:, :3] = k_matrix
    roi = context.profile.message("sensor_msgs/RegionOfInterest").new(
        x_offset=0, y_offset=0, height=0, width=0, do_rectify=False
    )
    return context.profile.message(CAMERA_INFO).new(
        header=context.header(optical_frame(rig.camera_frame_ids[k])),
        height=intrinsics.height,
        width=intrinsics.width,
        distortion_model="plumb_bob",
        D=np.zeros(5),
        K=k_matrix.reshape(-1),
        R=np.eye(3).reshape(-1),
        P=projection.reshape(-1),
        binning_x=0,
        binning_y=0,
        roi=roi,
    )
