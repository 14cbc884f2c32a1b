"""The camera renderer on OpenGL 3.3 through moderngl, in a headless EGL context.

No display server is needed: EGL's surfaceless platform with Mesa renders on the CPU
(llvmpipe). The static scene is uploaded once per map (`load`, before its first frame); a
frame's moving triangles are written to a buffer reused across frames. A vertex carries
its shaded, semantic and instance colours; each colour mode's vertex array reads only its
own, and depth mode's program writes the distance along the optical axis to a float32
target. Only the static scene's tiles inside the view frustum are drawn, far ones at
their coarse level (egosim.sensors.scene_tiles).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from egosim.sensors.camera import CameraMode, scene_matrices
from egosim.sensors.camera_labels import SEMANTIC_COLORS, SemanticClass
from egosim.sensors.camera_mesh import Mesh
from egosim.sensors.camera_render import SKY_RGB, RenderRequest
from egosim.sensors.camera_scene import StaticScene
from egosim.sensors.errors import RendererUnavailableError
from egosim.sensors.scene_tiles import visible_ranges

if TYPE_CHECKING:  # moderngl is imported where a renderer opens (open_renderer)
    import moderngl

COLOR_VERTEX_SHADER = """
#version 330
uniform mat4 clip_from_scene;
in vec3 in_position;
in vec3 in_color;
flat out vec3 v_color;
void main() {
    gl_Position = clip_from_scene * vec4(in_position, 1.0);
    v_color = in_color;
}
"""

COLOR_FRAGMENT_SHADER = """
#version 330
flat in vec3 v_color;
out vec4 f_color;
void main() {
    f_color = vec4(v_color, 1.0);
}
"""

DEPTH_VERTEX_SHADER = """
#version 330
uniform mat4 clip_from_scene;
uniform mat4 eye_from_scene;
in vec3 in_position;
out float v_depth;
void main() {
    vec4 point = vec4(in_position, 1.0);
    gl_Position = clip_from_scene * point;
    v_depth = -(eye_from_scene * point).z;
}
"""

DEPTH_FRAGMENT_SHADER = """
#version 330
in float v_depth;
out vec4 f_color;
void main() {
    f_color = vec4(v_depth, 0.0, 0.0, 1.0);
}
"""

SYSTEM_PACKAGES = ("libegl1", "libgl1", "libegl-mesa0", "libgl1-mesa-dri")
"""Debian packages EGL rendering on the CPU needs (the Makefile installs them)."""

BACKGROUND = {
    CameraMode.RGB: SKY_RGB,
    CameraMode.SEMANTIC: SEMANTIC_COLORS[SemanticClass.SKY],
    CameraMode.INSTANCE: (0, 0, 0),
}
VERTEX = np.dtype(
    [("position", "<f4", 3), ("color", "u1", 4), ("semantic", "u1", 4), ("instance", "u1", 4)]
)
# Each mode reads the position and only its own colour of a vertex (depth: no colour),
# so the rasteriser fetches and carries no attribute the image does not use.
MODE_LAYOUTS = {
    CameraMode.RGB: ("3f 3f1 1x 8x", ("in_position", "in_color")),
    CameraMode.SEMANTIC: ("3f 4x 3f1 1x 4x", ("in_position", "in_color")),
    CameraMode.INSTANCE: ("3f 8x 3f1 1x", ("in_position", "in_color")),
    CameraMode.DEPTH: ("3f 12x", ("in_position",)),
}


def vertex_bytes(mesh: Mesh) -> bytes:
    vertices = np.zeros(len(mesh), dtype=VERTEX)
    vertices["position"] = mesh.positions
    vertices["color"][:, :3] = mesh.colors
    vertices["semantic"][:, :3] = mesh.semantic
    vertices["instance"][:, :3] = mesh.instance
    return vertices.tobytes()


class GlRenderer:
    """CameraRenderer on a moderngl context (see open_renderer)."""

    def __init__(self, context: moderngl.Context) -> None:
        self._ctx = context
        color = context.program(
            vertex_shader=COLOR_VERTEX_SHADER, fragment_shader=COLOR_FRAGMENT_SHADER
        )
        depth = context.program(
            vertex_shader=DEPTH_VERTEX_SHADER, fragment_shader=DEPTH_FRAGMENT_SHADER
        )
        self._programs = {mode: depth if mode is CameraMode.DEPTH else color for mode in CameraMode}
        self._clip_from_scene = {
            mode: _uniform(program, "clip_from_scene") for mode, program in self._programs.items()
        }
        self._eye_from_scene = _uniform(depth, "eye_from_scene")
        self._scene: StaticScene | None = None
        self._static: tuple[moderngl.Buffer, dict[CameraMode, moderngl.VertexArray]] | None = None
        self._dynamic_buffer = context.buffer(reserve=VERTEX.itemsize * 3, dynamic=True)
        self._dynamic_arrays = self._vertex_arrays(self._dynamic_buffer)
        self._targets: dict[tuple[int, int, bool], moderngl.Framebuffer] = {}

    @property
    def description(self) -> str:
        info = self._ctx.info
        return f"OpenGL {info['GL_VERSION']} on {info['GL_RENDERER']}"

    def _vertex_arrays(self, buffer: moderngl.Buffer) -> dict[CameraMode, moderngl.VertexArray]:
        return {
            mode: self._ctx.vertex_array(self._programs[mode], [(buffer, layout, *attributes)])
            for mode, (layout, attributes) in MODE_LAYOUTS.items()
        }

    def _framebuffer(self, width: int, height: int, depth_mode: bool) -> moderngl.Framebuffer:
        key = (width, height, depth_mode)
        if key not in self._targets:
            ctx = self._ctx
            colour = (
                ctx.renderbuffer((width, height), components=1, dtype="f4")
                if depth_mode
                else ctx.renderbuffer((width, height), components=4)
            )
            depth = ctx.depth_renderbuffer((width, height))
            self._targets[key] = ctx.framebuffer(color_attachments=[colour], depth_attachment=depth)
        return self._targets[key]

    def load(self, scene: StaticScene) -> None:
        """Upload `scene`'s vertices, in place of the scene loaded before (if another)."""
        if self._scene is scene:
            return
        if self._static is not None:
            buffer, arrays = self._static
            for array in arrays.values():
                array.release()
            buffer.release()
        buffer = self._ctx.buffer(vertex_bytes(scene.mesh))
        self._static = (buffer, self._vertex_arrays(buffer))
        self._scene = scene

    def _static_arrays(self, scene: StaticScene) -> dict[CameraMode, moderngl.VertexArray]:
        self.load(scene)
        assert self._static is not None
        return self._static[1]

    def render(self, request: RenderRequest) -> npt.NDArray[np.uint8] | npt.NDArray[np.float32]:
        ctx, mode = self._ctx, request.mode
        intrinsics = request.intrinsics
        width, height = intrinsics.width, intrinsics.height
        depth_mode = mode is CameraMode.DEPTH
        framebuffer = self._framebuffer(width, height, depth_mode)
        framebuffer.use()
        ctx.viewport = (0, 0, width, height)
        ctx.enable(ctx.DEPTH_TEST)
        ctx.disable(ctx.CULL_FACE)
        if depth_mode:
            framebuffer.clear(red=math.inf, green=0.0, blue=0.0, alpha=0.0, depth=1.0)
        else:
            r, g, b = (c / 255.0 for c in BACKGROUND[mode])
            framebuffer.clear(red=r, green=g, blue=b, alpha=1.0, depth=1.0)

        eye, clip = scene_matrices(
            request.view, intrinsics, request.near_m, request.far_m, request.scene.origin
        )
        self._clip_from_scene[mode].write(clip.T.astype("f4").tobytes())
        if depth_mode:
            self._eye_from_scene.write(eye.T.astype("f4").tobytes())

        static = self._static_arrays(request.scene)[mode]
        eye_in_scene = request.view.origin - request.scene.origin
        focal_px = max(intrinsics.fx, intrinsics.fy)
        for first, count in visible_ranges(request.scene.tiles, clip, eye_in_scene, focal_px):
            static.render(vertices=count, first=first)
        if len(request.frame):
            data = vertex_bytes(request.frame)
            if len(data) > self._dynamic_buffer.size:
                self._dynamic_buffer.orphan(len(data))
            self._dynamic_buffer.write(data)
            self._dynamic_arrays[mode].render(vertices=len(request.frame))

        if depth_mode:
            raw = framebuffer.read(components=1, dtype="f4", alignment=1)
            image = np.frombuffer(raw, dtype="<f4").reshape(height, width)
            return np.ascontiguousarray(image[::-1])
        raw = framebuffer.read(components=3, alignment=1)
        pixels = np.frombuffer(raw, dtype=np.uint8).reshape(height, width, 3)
        return np.ascontiguousarray(pixels[::-1])


def _uniform(program: moderngl.Program, name: str) -> moderngl.Uniform:
    """The uniform `name` of `program` (a program's members are also its attributes and
    varyings)."""
    from moderngl import Uniform  # noqa: PLC0415 - a program exists: open_renderer imported it

    member = program[name]
    assert isinstance(member, Uniform), f"{name} is no uniform of the shader program"
    return member


def open_renderer() -> GlRenderer:
    """The OpenGL renderer on a headless EGL context; RendererUnavailableError if none."""
    try:
        import moderngl  # noqa: PLC0415 - a missing engine is reported, not fatal
    except ImportError as error:
        raise RendererUnavailableError(f"moderngl is not installed ({error})") from None
    try:
        # The runtime libraries' sonames (libegl1, libgl1), not the -dev packages' links.
        # moderngl's stub types every keyword setting as a dict; glcontext takes strings.
        context = moderngl.create_context(
            standalone=True,
            require=330,
            backend="egl",  # type: ignore[arg-type]
            libgl="libGL.so.1",  # type: ignore[arg-type]
            libegl="libEGL.so.1",  # type: ignore[arg-type]
        )
    except Exception as error:  # glcontext raises bare Exceptions for a missing libEGL/driver
        raise RendererUnavailableError(
            f"no OpenGL 3.3 through EGL ({error}); install {' '.join(SYSTEM_PACKAGES)}"
        ) from None
    return GlRenderer(context)
