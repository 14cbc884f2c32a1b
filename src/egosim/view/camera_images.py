"""The cameras' images for the page: each colour camera rendered and encoded at most
IMAGE_RATE_HZ, and only when a frame is taken (a browser watches), so a view nobody
looks at costs the cameras nothing and one that is watched a few frames a second."""

from __future__ import annotations

from ..bridge import BridgeContext
from ..sensors.camera import CameraMode
from .messages import ImageSource, SensorImage

#: How often the page's copy of a camera's image is renewed, Hz of simulation time.
IMAGE_RATE_HZ = 2.0


def camera_image_sources(context: BridgeContext) -> list[ImageSource]:
    """One source per colour camera of the main ego (none when the cameras are off)."""
    if context.cameras is None:
        return []
    return [
        _source(context, k)
        for k, camera in enumerate(context.sensors.cameras)
        if camera.config.mode is not CameraMode.DEPTH
    ]


def _source(context: BridgeContext, k: int) -> ImageSource:
    latest: list[SensorImage] = []

    def image() -> SensorImage | None:
        rig, world, cameras = context.sensors, context.world, context.cameras
        if cameras is None:
            return None
        if latest and world.sim_time - latest[0].stamp < 1.0 / IMAGE_RATE_HZ:
            return latest[0]
        data = cameras.encoded_image(rig, world, k)
        mime = f"image/{rig.cameras[k].format.value}"
        latest[:] = [SensorImage(rig.camera_frame_ids[k], mime, data, world.sim_time)]
        return latest[0]

    return image
