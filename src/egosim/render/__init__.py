"""Rendering engines behind egosim.sensors.camera_render.CameraRenderer.

`open_renderer()` gives the default engine (OpenGL 3.3 on a headless EGL context: Mesa's
llvmpipe on the CPU, or a GPU when the system has one), or raises
RendererUnavailableError saying why it cannot run here.
"""

from egosim.render.gl import GlRenderer, open_renderer

__all__ = ["GlRenderer", "open_renderer"]
