"""The view's stage in the tick pipeline: frames while watched, the LiDAR in the map
frame while a browser shows it, the measured real-time factor."""

from __future__ import annotations

import json
import math

import numpy as np

from egosim.bridge import BridgeContext
from egosim.view.controls import ViewControls
from egosim.view.hub import FrameHub
from egosim.view.stage import MAX_LIDAR_POINTS, ViewStage

DT = 0.01


class Clock:
    def __init__(self) -> None:
        self.now = 0.0

    def __call__(self) -> float:
        return self.now


def installed(context: BridgeContext, **options) -> tuple[ViewStage, FrameHub, Clock]:
    clock = Clock()
    hub = FrameHub(monotonic=clock)
    stage = ViewStage(context, hub, ViewControls(context, None), "real", monotonic=clock, **options)
    context.pipeline = context.pipeline.with_stage(stage.stage(), after="clock")
    return stage, hub, clock


def tick(context: BridgeContext, clock: Clock, seconds: float, wall_per_tick: float = DT) -> None:
    for _ in range(round(seconds / DT)):
        context.tick(DT)
        clock.now += wall_per_tick


def test_the_view_is_the_last_stage_and_takes_frames_only_while_watched(
    town: BridgeContext,
) -> None:
    _, hub, clock = installed(town)
    assert town.pipeline.names[-1] == "view"
    tick(town, clock, 1.0)
    assert hub.sequence == 0
    hub.clients = 1
    tick(town, clock, 1.0)
    assert 28 <= hub.sequence <= 31
    frame = json.loads(hub.latest()[1])
    assert 0 <= town.world.sim_time - frame["sim_time"] < 1 / 30  # the newest frame


def test_the_real_time_factor_is_measured_against_the_wall_clock(town: BridgeContext) -> None:
    _, hub, clock = installed(town)
    hub.clients = 1
    tick(town, clock, 3.0, wall_per_tick=DT / 2)  # twice as fast as real time
    rtf = json.loads(hub.latest()[1])["real_time_factor"]
    assert math.isclose(rtf, 2.0, rel_tol=0.02)


def test_lidar_points_are_sent_in_the_map_frame_while_shown(town: BridgeContext) -> None:
    _, hub, clock = installed(town, lidar_on=True)
    hub.clients = 1
    tick(town, clock, 0.2)
    assert json.loads(hub.latest()[1])["lidar"] is None  # no browser shows the layer
    hub.lidar_wanted = True
    tick(town, clock, 0.2)
    points = np.array(json.loads(hub.latest()[1])["lidar"]).reshape(-1, 2)
    assert 0 < len(points) <= MAX_LIDAR_POINTS
    pose = town.world.ego_status(0).pose
    reach = np.hypot(points[:, 0] - pose.x, points[:, 1] - pose.y)
    assert reach.max() <= town.sensors.lidar.config.max_range_m + 3.0
    assert np.median(reach) > 2.0  # around the ego, not at the map's origin
