"""The main ego's cameras at run time: the renderer, the map's scene, one image per camera.

The static scene is built once per map (again after a scenario load changes the map),
and kept for the next rig on the same map (maps are immutable, and egosim.maps hands out
the map it read before for the same source: a batch worker builds each scene once).
A camera's mount comes from the SensorRig (SensorPosControl moves it there).
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
from ...world import World
from ...world.map import LaneMap
from .sensor_rig import MAIN_EGO, SensorRig

log = logging.getLogger(__name__)

SCENES_KEPT = 4
static_scene = lru_cache(maxsize=SCENES_KEPT)(build_static_scene)
"""The static scene of a map, built once per map object."""


class CameraRig:
    def __init__(self, renderer: CameraRenderer) -> None:
        self.renderer = renderer

    def scene(self, lane_map: LaneMap) -> StaticScene:
        return static_scene(lane_map)

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
            self.scene(world.map),
            world.ego_status(MAIN_EGO).pose,
            world.objects(),
            world.signals.aspects(),
            (world.egos[MAIN_EGO].unique_id,),
        )


def open_camera_rig(
    sensors: SensorRig, open_renderer: Callable[[], CameraRenderer], lane_map: LaneMap
) -> CameraRig | None:
    """A CameraRig on the renderer `open_renderer` gives, its scene of `lane_map` built
    (so the first frame does not stall the loop), or None (logged in one line) when no
    camera is configured or no renderer can run here."""
    if not sensors.cameras:
        return None
    try:
        renderer = open_renderer()
    except RendererUnavailableError as error:
        log.warning("cameras off: %s", error)
        return None
    described = getattr(renderer, "description", type(renderer).__name__)
    log.info("cameras: %d, rendered with %s", len(sensors.cameras), described)
    rig = CameraRig(renderer)
    rig.scene(lane_map)
    return rig
