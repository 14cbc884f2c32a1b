"""A mounted camera over world state: the frame's triangles, the view, one image.

The renderer is injected (see egosim.sensors.camera_render), so this module stays pure
and the engine can be swapped or faked in tests.
"""

from __future__ import annotations

from collections.abc import Iterable

import numpy as np
import numpy.typing as npt

from egosim.sensors.camera import CameraConfig, CameraView, scene_matrices
from egosim.sensors.camera_frame_mesh import build_frame_mesh
from egosim.sensors.camera_render import CameraRenderer, RenderRequest
from egosim.sensors.camera_scene import StaticScene
from egosim.world.traffic.objects import ObjectTable
from egosim.world.vehicle import Pose

Image = npt.NDArray[np.uint8] | npt.NDArray[np.float32]


def capture(
    config: CameraConfig,
    renderer: CameraRenderer,
    scene: StaticScene,
    vehicle_pose: Pose,
    objects: ObjectTable,
    aspects: npt.ArrayLike,
    hidden_ids: Iterable[int] = (),
) -> Image:
    """The image of a camera mounted at `config.mount` on base_link at `vehicle_pose`.

    `objects` are drawn but those in `hidden_ids` (the vehicle carrying the camera) and
    those out of view; `aspects` are the lights' aspects in `scene.lights` order.
    """
    view = CameraView.of(vehicle_pose, config.mount)
    intrinsics = config.intrinsics()
    _, clip = scene_matrices(view, intrinsics, config.near_m, config.far_m, scene.origin)
    request = RenderRequest(
        scene=scene,
        frame=build_frame_mesh(scene, objects, aspects, hidden_ids, clip),
        view=view,
        intrinsics=intrinsics,
        mode=config.mode,
        near_m=config.near_m,
        far_m=config.far_m,
    )
    return renderer.render(request)
