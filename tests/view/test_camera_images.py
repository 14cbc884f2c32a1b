"""The page shows each colour camera's image, renewed a few times a second."""

from __future__ import annotations

import io

import numpy as np
from PIL import Image

from egosim.bridge import ClockMode, simulation_context
from egosim.bridge.protocol.network import parse_network_settings
from egosim.view.camera_images import IMAGE_RATE_HZ, camera_image_sources
from egosim.world import World
from egosim.world.map import build_builtin_map
from tests.sensors.camera_world import renderer

CAMERAS = """
sensors:
  cameras:
    - {width: 160, height: 120}
    - {mode: depth, width: 80, height: 60}
"""


def test_each_colour_camera_gives_a_jpeg_renewed_at_its_rate() -> None:
    settings = parse_network_settings(CAMERAS, "net.yaml")
    context = simulation_context(
        World(build_builtin_map("straight")),
        settings=settings,
        clock_mode=ClockMode.SIM,
        open_renderer=renderer,
    )
    (source,) = camera_image_sources(context)  # the depth camera is not shown
    first = source()
    assert first is not None and first.mime == "image/jpeg" and first.name == "Camera"
    pixels = np.asarray(Image.open(io.BytesIO(first.data)))
    assert pixels.shape == (120, 160, 3)
    context.tick(0.01)
    assert source() is first  # renewed only every 1 / IMAGE_RATE_HZ s
    for _ in range(round(100 / IMAGE_RATE_HZ)):
        context.tick(0.01)
    renewed = source()
    assert renewed is not first and renewed is not None
    assert renewed.stamp > first.stamp


def test_no_cameras_no_images() -> None:
    context = simulation_context(World(build_builtin_map("straight")))
    assert camera_image_sources(context) == []
