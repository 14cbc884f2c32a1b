"""Wiring: the live view of a running simulator (snapshot stage + web server)."""

from __future__ import annotations

import logging
from dataclasses import dataclass

from ..app.attachments import Attach, RunningSimulator
from .camera_images import camera_image_sources
from .controls import ViewControls
from .hub import FrameHub
from .server import ViewBackend, ViewServer, ViewServerError
from .snapshot import encode, map_snapshot
from .stage import ViewStage

log = logging.getLogger(__name__)

DEFAULT_HOST = "127.0.0.1"
DEFAULT_PORT = 8765


@dataclass(frozen=True)
class ViewOptions:
    host: str = DEFAULT_HOST
    port: int = DEFAULT_PORT
    readonly: bool = False


class LiveView:
    """The view attached to one run: its server (its stage is in the tick pipeline)."""

    def __init__(self, server: ViewServer) -> None:
        self.server = server

    def close(self) -> None:
        self.server.close()


class NoView:
    """What runs when the view could not start: nothing."""

    def close(self) -> None:
        pass


def live_view(options: ViewOptions) -> Attach:
    def attach(running: RunningSimulator) -> LiveView | NoView:
        context = running.context
        clock_mode = running.options.clock
        hub = FrameHub()
        controls = ViewControls(context, running.startup_scenario)
        stage = ViewStage(
            context,
            hub,
            controls,
            clock_mode.value,
            lidar_on=context.row("lidar").enabled,
            controls_enabled=not options.readonly,
            images=camera_image_sources(context),
        )
        backend = ViewBackend(
            hub=hub,
            inbox=running.inbox,
            prepare=controls.prepare,
            apply=controls.apply,
            capture=stage.capture,
            history=lambda: encode(stage.history.message()),
            map_json=lambda: encode(map_snapshot(context.world.map)),
            system_state=running.node.master.get_system_state,
            hello={
                "type": "hello",
                "clock_mode": clock_mode.value,
                "egosim_node": running.node.name,
            },
        )
        server = ViewServer(backend, options.host, options.port, options.readonly)
        try:
            server.start()
        except ViewServerError as error:
            # The view is a window on the simulation, not part of it: run on without it.
            log.error("live view not started: %s (--view-port picks another port)", error)
            print(f"egosim: no view ({error})", flush=True)
            return NoView()
        # Last in the tick: the view sees what was published.
        pipeline = context.pipeline
        context.pipeline = pipeline.with_stage(stage.stage(), after=pipeline.names[-1])
        context.pipeline.loop_time = pipeline.loop_time
        print(f"egosim: view at {server.url}", flush=True)
        return LiveView(server)

    return attach
