"""The view's part of every tick (loop thread): finish a single step, keep the plots'
history, and take a frame for the browsers when one is due. It never waits on the
server."""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence

import numpy as np

from ..bridge import BridgeContext, Stage
from ..sensors import sensor_in_map
from ..world.vehicle import Pose
from .controls import ViewControls
from .history import PlotHistory
from .hub import FrameHub
from .messages import ImageSource
from .snapshot import FrameInfo, capture_frame

#: LiDAR scans the view casts itself, per second at most, while a browser shows them.
LIDAR_RATE_HZ = 5.0
#: Points sent of one scan at most (every k-th point beyond that).
MAX_LIDAR_POINTS = 4000
#: Weight of the newest measurement in the real-time factor shown.
RTF_SMOOTHING = 0.2


class ViewStage:
    def __init__(
        self,
        context: BridgeContext,
        hub: FrameHub,
        controls: ViewControls,
        clock_mode: str,
        *,
        lidar_on: bool = False,
        images: Sequence[ImageSource] = (),
        controls_enabled: bool = True,
        monotonic: Callable[[], float] = time.monotonic,
    ) -> None:
        self.context = context
        self.hub = hub
        self.controls = controls
        self._clock_mode = clock_mode
        self._lidar_on = lidar_on
        self._images = images
        self._controls_enabled = controls_enabled
        self._monotonic = monotonic
        self._rtf: float | None = None
        self._last: tuple[float, float] | None = None  # (wall, sim) at the last frame
        self._lidar_points: np.ndarray | None = None
        self._lidar_at = -float("inf")
        self.history = PlotHistory()
        """The last minute of the plotted series, for pages that open later."""

    def stage(self) -> Stage[BridgeContext]:
        """This as the "view" stage of the tick pipeline."""
        return Stage("view", lambda context, tick: self.after_step())

    def after_step(self) -> None:
        """Run after every tick: the cheap checks, a history sample when one is due, and
        a frame when the hub wants one."""
        if self.controls.pause_after_step:
            self.controls.pause_after_step = False
            self.context.world.paused = True
        self.controls.release_silent_keyboards()
        self.history.record(self.context)
        if self.hub.due():
            self.capture()

    def capture(self) -> None:
        """Take a frame now and hand it to the hub (loop thread)."""
        clock_mode = "sync" if self.context.sync.holds_time else self._clock_mode
        info = FrameInfo(clock_mode, self._real_time_factor(), self._controls_enabled)
        frame = capture_frame(self.context, info, self._lidar(), self._images)
        self.hub.offer(frame)

    def _real_time_factor(self) -> float | None:
        wall, sim = self._monotonic(), self.context.world.sim_time
        last, self._last = self._last, (wall, sim)
        if last is None or wall <= last[0]:
            return self._rtf
        measured = (sim - last[1]) / (wall - last[0])
        if self._rtf is None or measured < 0:
            self._rtf = max(measured, 0.0)
        else:
            self._rtf += RTF_SMOOTHING * (measured - self._rtf)
        return self._rtf

    def _lidar(self) -> np.ndarray | None:
        """The main ego's LiDAR points in the map frame (x, y), recast at LIDAR_RATE_HZ."""
        rig = self.context.sensors
        if not (self._lidar_on and self.hub.lidar_wanted):
            self._lidar_points = None
            return None
        now = self._monotonic()
        if now - self._lidar_at >= 1.0 / LIDAR_RATE_HZ:
            self._lidar_at = now
            world = self.context.world
            points = rig.scan(world, self.context.objects())[:, :3].astype(np.float64)
            if len(points) > MAX_LIDAR_POINTS:
                points = points[:: -(-len(points) // MAX_LIDAR_POINTS)]
            pose: Pose = world.ego_status(0).pose
            origin, rotation = sensor_in_map(pose, rig.lidar.config.mount)
            self._lidar_points = (points @ rotation.T + origin)[:, :2]
        return self._lidar_points
