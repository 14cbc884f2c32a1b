"""The one thing a camera asks of a rendering engine, so engines can be swapped.

A renderer rasterises a static scene plus a frame's moving triangles through a pinhole
camera and reads one image back: RGB, semantic or instance colours as (H, W, 3) uint8,
or depth as (H, W) float32 metres along the optical axis (+inf where nothing is hit).
Rows run top to bottom. The same request always gives the same array.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import numpy as np
import numpy.typing as npt

from egosim.sensors.camera import CameraMode, CameraView, Intrinsics
from egosim.sensors.camera_mesh import Mesh
from egosim.sensors.camera_scene import StaticScene

SKY_RGB = (135, 190, 235)
"""The clear sky behind everything in an RGB image."""


@dataclass(frozen=True, eq=False)
class RenderRequest:
    scene: StaticScene
    frame: Mesh
    view: CameraView
    intrinsics: Intrinsics
    mode: CameraMode
    near_m: float
    far_m: float


class CameraRenderer(Protocol):
    def load(self, scene: StaticScene) -> None:
        """Make `scene` ready to draw (an engine uploads it here), so that its first frame
        costs no more than the next. A request for a scene not loaded loads it first."""
        ...

    def render(self, request: RenderRequest) -> npt.NDArray[np.uint8] | npt.NDArray[np.float32]:
        """The image of `request` (see the module docstring)."""
        ...
