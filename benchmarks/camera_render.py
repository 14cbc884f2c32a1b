"""Camera rendering cost on the town map with its default traffic, and the engines compared.

- render + encode: one RGB frame (JPEG, quality 90) of the ego's front camera, and each
  label mode (PNG) and depth (raw float32), at 640 x 480 and 1280 x 720;
- engines: the static town scene alone, rendered and read back at 640 x 480 by each
  candidate that is installed: moderngl (OpenGL 3.3 on EGL, Mesa llvmpipe) and Panda3D's
  p3tinydisplay software renderer (`pip install panda3d`, not a dependency).

Usage: .venv/bin/python benchmarks/camera_render.py [--frames 60]
"""

from __future__ import annotations

import argparse
import statistics
import time
from collections.abc import Callable

import numpy as np

from egosim.render import open_renderer
from egosim.sensors.camera import CameraConfig, CameraMode, CameraView
from egosim.sensors.camera_capture import capture
from egosim.sensors.camera_mesh import Mesh
from egosim.sensors.camera_render import RenderRequest
from egosim.sensors.camera_scene import StaticScene, build_static_scene
from egosim.sensors.image_encoding import ImageFormat, depth_bytes, encode_image
from egosim.world import World
from egosim.world.map import build_builtin_map
from egosim.world.scenario import load_default_scenario

WARMUP_STEPS = 200


def _median_ms(action: Callable[[], object], frames: int) -> str:
    """Wall time per frame, and the process's CPU time per frame (every thread, so the
    rasteriser's too): on a shared machine the CPU time says what a frame costs."""
    action()
    durations = []
    cpu_start = time.process_time()
    for _ in range(frames):
        start = time.perf_counter()
        action()
        durations.append((time.perf_counter() - start) * 1e3)
    cpu_ms = (time.process_time() - cpu_start) * 1e3 / frames
    p95 = sorted(durations)[int(0.95 * len(durations))]
    return (
        f"median {statistics.median(durations):.1f} ms, min {min(durations):.1f} ms, "
        f"p95 {p95:.1f} ms; CPU {cpu_ms:.1f} ms/frame"
    )


def _panda3d_frame(
    scene: StaticScene, config: CameraConfig, view: CameraView
) -> Callable[[], object] | None:
    """Render + read back the static scene with Panda3D's software renderer, if installed."""
    try:
        from panda3d.core import (  # noqa: PLC0415
            Geom,
            GeomNode,
            GeomTriangles,
            GeomVertexData,
            GeomVertexFormat,
            GraphicsOutput,
            Texture,
            loadPrcFileData,
        )
    except ImportError:
        return None
    loadPrcFileData(
        "",
        f"load-display p3tinydisplay\nwindow-type offscreen\nwin-size {config.width} "
        f"{config.height}\naudio-library-name null\nnotify-level error\n",
    )
    from direct.showbase.ShowBase import ShowBase  # noqa: PLC0415

    base = ShowBase()
    mesh = scene.mesh
    data = GeomVertexData("scene", GeomVertexFormat.getV3c4(), Geom.UHStatic)
    data.setNumRows(len(mesh))
    vertices = np.zeros(len(mesh), dtype=[("p", "<f4", 3), ("c", "u1", 4)])
    vertices["p"] = mesh.positions
    vertices["c"][:, :3] = mesh.colors[:, ::-1]
    vertices["c"][:, 3] = 255
    memoryview(data.modifyArray(0)).cast("B")[:] = vertices.tobytes()
    triangles = GeomTriangles(Geom.UHStatic)
    triangles.addNextVertices(len(mesh))
    geom = Geom(data)
    geom.addPrimitive(triangles)
    node = GeomNode("scene")
    node.addGeom(geom)
    base.render.attachNewNode(node)
    base.disableMouse()
    eye = view.origin - scene.origin
    forward = view.optical_to_map[:, 2]
    base.camera.setPos(*eye)
    base.camera.lookAt(*(eye + forward))
    vertical = config.fov_deg
    horizontal = np.degrees(
        2 * np.arctan(config.width / config.height * np.tan(np.radians(vertical) / 2))
    )
    base.camLens.setFov(horizontal, vertical)
    base.camLens.setNearFar(config.near_m, config.far_m)
    texture = Texture()
    base.win.addRenderTexture(texture, GraphicsOutput.RTMCopyRam)

    def frame() -> object:
        base.graphicsEngine.renderFrame()
        return np.frombuffer(texture.getRamImageAs("RGB"), np.uint8)

    return frame


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--frames", type=int, default=60)
    args = parser.parse_args()
    lane_map = build_builtin_map("town")
    start = time.perf_counter()
    scene = build_static_scene(lane_map)
    build_s = time.perf_counter() - start
    print(f"town scene: {len(scene.mesh) // 3} triangles, built in {build_s:.2f} s")
    world = World(lane_map, load_default_scenario())
    for _ in range(WARMUP_STEPS):
        world.step()
    renderer = open_renderer()
    print(f"renderer: {renderer.description}")
    pose = world.ego_status(0).pose
    objects, aspects = world.objects(), world.signals.aspects()
    ego_id = [world.egos[0].unique_id]

    for width, height in ((640, 480), (1280, 720)):
        for mode in CameraMode:
            config = CameraConfig(width=width, height=height, mode=mode)

            def frame(config: CameraConfig = config) -> bytes:
                image = capture(config, renderer, scene, pose, objects, aspects, ego_id)
                if config.mode is CameraMode.DEPTH:
                    return depth_bytes(image)  # type: ignore[arg-type]
                image_format = (
                    ImageFormat.JPEG if config.mode is CameraMode.RGB else ImageFormat.PNG
                )
                return encode_image(image, image_format)  # type: ignore[arg-type]

            print(
                f"{width}x{height} {mode.value} render + encode: {_median_ms(frame, args.frames)}"
            )

    config = CameraConfig()
    view = CameraView.of(pose, config.mount)
    request = RenderRequest(
        scene, Mesh.empty(), view, config.intrinsics(), CameraMode.RGB, config.near_m, config.far_m
    )
    timing = _median_ms(lambda: renderer.render(request), args.frames)
    print(f"engine moderngl/EGL static scene 640x480: {timing}")
    panda = _panda3d_frame(scene, config, view)
    if panda is None:
        print("engine panda3d p3tinydisplay: not installed (pip install panda3d)")
    else:
        print(
            f"engine panda3d p3tinydisplay static scene 640x480: {_median_ms(panda, args.frames)}"
        )


if __name__ == "__main__":
    main()
