"""The MORAI protocol: the topic/service table, its handlers, and the tick pipeline.

`simulation_context` builds what the handlers see; a `Bridge` binds the table's rows
to a ROS node; `context.tick(dt)` advances the simulation through the pipeline::

    bridge = Bridge(node, settings, HANDLERS, inbox)
    context = simulation_context(world, settings=settings, bridge=bridge)
    bridge.open(context)
    context.tick(0.01)          # replay, autopilots, world, clock, publish

Without a node (tests, benchmarks), leave `bridge` out: the pipeline has no publish
stage and handlers can be called directly with `context.row(key)`.

Two storeys. At the bottom, protocol/: the table, the network and sensor settings that
override it, the protocol's codes, units and releases. Above it, the engine in this
folder: the context handlers see (context.py), the binding of rows to the node
(core.py), which handler serves each row (bindings.py), the tick pipeline and its
stages (pipeline.py, stages.py), the header clock and /clock (clock.py, sim_clock.py),
and each ego's session with what its control mode means (ego_session.py,
control_modes.py). The handlers are grouped by what they serve: egos/, scene/,
sensors/ (cameras too), sync/ and replay/.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from contextlib import AbstractContextManager, nullcontext
from pathlib import Path

from ..msgs import get_profile
from ..replay import ReplaySession
from ..sensors.camera_render import CameraRenderer
from ..world import World
from .bindings import HANDLERS
from .clock import ClockMode, HeaderClock
from .context import BridgeContext, SessionState
from .core import Bridge, Handlers, Tap
from .pipeline import Stage, Tick, TickPipeline
from .protocol.codes import ControlMode
from .protocol.network import NetworkSettings, default_network_settings, load_network_settings
from .protocol.releases import CANONICAL_PROFILE
from .protocol.table import Direction, Row
from .replay.replay_rows import replay_topics
from .sensors.camera_rig import open_camera_rig
from .sensors.sensor_rig import sensor_rig_of
from .stages import standard_pipeline
from .sync.sync_session import SyncSession

__all__ = [
    "CANONICAL_PROFILE",
    "HANDLERS",
    "Bridge",
    "BridgeContext",
    "ClockMode",
    "ControlMode",
    "Direction",
    "Handlers",
    "HeaderClock",
    "NetworkSettings",
    "Row",
    "SessionState",
    "Stage",
    "SyncSession",
    "Tap",
    "Tick",
    "TickPipeline",
    "default_network_settings",
    "load_network_settings",
    "simulation_context",
    "standard_pipeline",
]


def simulation_context(
    world: World,
    *,
    settings: NetworkSettings | None = None,
    clock_mode: ClockMode = ClockMode.SIM,
    data_roots: Sequence[Path] = (),
    bridge: Bridge | None = None,
    hold_output: Callable[[], AbstractContextManager[None]] = nullcontext,
    wall_clock: Callable[[], float] | None = None,
    open_renderer: Callable[[], CameraRenderer] | None = None,
    camera_scene_at_first_frame: bool = False,
) -> BridgeContext:
    """Everything the row handlers need around `world`, with the standard tick pipeline.

    With a `bridge` (bound to a ROS node) the pipeline publishes and additional egos'
    rows open at run time; without one, the simulation runs in-process. With
    `open_renderer` (the camera engine), the configured cameras render; the map's camera
    scene is built now, or with `camera_scene_at_first_frame` when a camera first renders.
    """
    settings = settings or default_network_settings()
    sensors = sensor_rig_of(settings, world.map.georef)
    cameras = (
        open_camera_rig(sensors, open_renderer, world.map, camera_scene_at_first_frame)
        if open_renderer is not None and settings.row("camera").enabled
        else None
    )
    world.command_timeout_s = settings.command_timeout_s
    clock = (
        HeaderClock(clock_mode, world)
        if wall_clock is None
        else HeaderClock(clock_mode, world, wall_clock)
    )
    return BridgeContext(
        profile=get_profile(CANONICAL_PROFILE),
        world=world,
        clock=clock,
        pipeline=standard_pipeline(bridge),
        settings=settings,
        sensors=sensors,
        cameras=cameras,
        replay=ReplaySession(data_roots, profile=CANONICAL_PROFILE, topics=replay_topics(settings)),
        sync=SyncSession(awaiting_client=clock_mode is ClockMode.SYNC),
        data_roots=tuple(data_roots),
        rows=bridge,
        hold_output=hold_output,
    )
