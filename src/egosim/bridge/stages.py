"""The standard stages of a tick, in order (see bridge/pipeline.py).

replay: move a playing bag's clock and show its frame; autopilots: command the egos
in auto mode; storyboard: an OpenSCENARIO storyboard decides and moves its entities;
world: World.step; clock: read the header clock for this tick's stamps;
publish: build and send every row that is due (only with a ROS node).
"""

from __future__ import annotations

from .context import BridgeContext
from .control_modes import drive_autopilots
from .core import Bridge
from .pipeline import Stage, Tick, TickPipeline
from .replay.replay_rows import advance_replay
from .scene.storyboard import step_storyboard

REPLAY = Stage[BridgeContext]("replay", lambda context, tick: advance_replay(context, tick.dt))
AUTOPILOTS = Stage[BridgeContext]("autopilots", lambda context, tick: drive_autopilots(context))
STORYBOARD = Stage[BridgeContext](
    "storyboard", lambda context, tick: step_storyboard(context, tick.dt)
)
WORLD = Stage[BridgeContext]("world", lambda context, tick: context.world.step(tick.dt))
CLOCK = Stage[BridgeContext]("clock", lambda context, tick: context.clock.tick(tick.dt))


def publish_stage(bridge: Bridge) -> Stage[BridgeContext]:
    """Publish every row of `bridge` that is due at the tick's loop time."""

    def publish(context: BridgeContext, tick: Tick) -> None:
        bridge.publish_due(tick.loop_time)

    return Stage("publish", publish)


def standard_pipeline(bridge: Bridge | None = None) -> TickPipeline[BridgeContext]:
    """replay -> autopilots -> storyboard -> world -> clock (-> publish, with a bridge)."""
    stages = [REPLAY, AUTOPILOTS, STORYBOARD, WORLD, CLOCK]
    if bridge is not None:
        stages.append(publish_stage(bridge))
    return TickPipeline(stages)
