"""The main ego's cameras at run time: the renderer, the map's static scene, one image per
camera.

The static scene is built where the rig is, from the world's map (a world keeps its map:
a scenario load must name the one running), and loaded into the renderer there, so the
first frame costs what the next ones do; or, asked to, when the first frame is taken
(a batch worker: most cases take none). It is kept for the next rig on the same map
(maps are immutable, and egosim.maps hands out the map it read before for the same
source: a batch worker builds each scene once). A camera's mount comes from the
SensorRig (SensorPosControl moves it there).
"""

from __future__ import annotations

import logging
from collections.abc import Callable
from dataclasses import replace
from functools import lru_cache

from ...sensors import RendererUnavailableError
from ...sensors.camera_capture import Image, capture
from ...sensors.camera_render import CameraRenderer
from ...sensors.camera_scene import StaticScene, build_static_scene
from ...sensors.image_encoding import encode_image
from ...world import World
from ...world.map import LaneMap
from .sensor_rig import MAIN_EGO, SensorRig

log = logging.getLogger(__name__)

SCENES_KEPT = 4
static_scene = lru_cache(maxsize=SCENES_KEPT)(build_static_scene)
"""The static scene of a map, built once per map object."""


class CameraRig:
    """The main ego's cameras on `renderer`, over the static scene `scene` gives (built
    and loaded into the renderer when first asked for)."""

    def __init__(self, renderer: CameraRenderer, scene: Callable[[], StaticScene]) -> None:
        self.renderer = renderer
        self._scene_of = scene
        self._scene: StaticScene | None = None

    @property
    def scene(self) -> StaticScene:
        if self._scene is None:
            self._scene = self._scene_of()
            self.renderer.load(self._scene)
        return self._scene

    def image(self, sensors: SensorRig, world: World, k: int) -> Image:
        """Camera k's image of the world as it is now; the main ego does not see itself."""
        camera = sensors.cameras[k]
        config = camera.config
        mount = sensors.placed_camera(world, k)
        if mount != config.mount:
            config = replace(config, mount=mount)
        return capture(
            config,
            self.renderer,
            self.scene,
            world.ego_status(MAIN_EGO).pose,
            world.objects(),
            world.signals.aspects(),
            (world.egos[MAIN_EGO].unique_id,),
        )

    def encoded_image(self, sensors: SensorRig, world: World, k: int) -> bytes:
        """Colour camera k's image of the world as it is now, encoded in the camera's
        format (JPEG or PNG)."""
        camera = sensors.cameras[k]
        pixels = self.image(sensors, world, k)
        return encode_image(pixels, camera.format, camera.config.jpeg_quality)  # type: ignore[arg-type]


def open_camera_rig(
    sensors: SensorRig,
    open_renderer: Callable[[], CameraRenderer],
    lane_map: LaneMap,
    scene_at_first_frame: bool = False,
) -> CameraRig | None:
    """A CameraRig on the renderer `open_renderer` gives, over the static scene of
    `lane_map` (built and loaded now, so the first frame does not stall the loop; with
    `scene_at_first_frame`, when the first frame is taken), or None (logged in one line)
    when no camera is configured or no renderer can run here."""
    if not sensors.cameras:
        return None
    try:
        renderer = open_renderer()
    except RendererUnavailableError as error:
        log.warning("cameras off: %s", error)
        return None
    described = getattr(renderer, "description", type(renderer).__name__)
    log.info("cameras: %d, rendered with %s", len(sensors.cameras), described)
    rig = CameraRig(renderer, lambda: static_scene(lane_map))
    if not scene_at_first_frame:
        rig.scene  # noqa: B018 (built and loaded now)
    return rig
