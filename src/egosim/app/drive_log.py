"""The drive as it happens, on `egosim run`'s console: every collision of an ego (with
whom, where) and every infraction the evaluation's rules find (red lights and stop lines
run, driving the wrong way, leaving the road), logged at INFO as each begins. Lane
departures, which every lane change makes, go to DEBUG.

It is the "drive log" stage of the tick pipeline, right after the world's step, with a
"drive log start" stage right before it that takes an ego's first sample from the world
before the step: a coarse sync tick (up to 1 s) may carry the ego over a stop line in its
very first step. Both are left out when nothing would be shown (the log level is above
INFO).
"""

from __future__ import annotations

import logging
import math

from ..bridge import BridgeContext, Stage, Tick, TickPipeline
from ..evaluation import (
    COLLISION_KINDS,
    Infraction,
    InfractionKind,
    InfractionWatch,
    ego_sample,
)
from ..evaluation.rules import Sample
from ..world import World

log = logging.getLogger("egosim.drive")

JUMP_M = 5.0
"""An ego that moved this much farther in one step than its speed carries it was placed (a
scenario load, a teleport, a replay's seek): its rules start afresh there rather than see
it cross what it skipped. (A step may be a sync tick of up to 1 s: at 30 m/s, 30 m.)"""

_LABELS = {
    InfractionKind.COLLISION_PEDESTRIAN: "collision (pedestrian)",
    InfractionKind.COLLISION_VEHICLE: "collision (vehicle)",
    InfractionKind.COLLISION_STATIC: "collision (obstacle)",
    InfractionKind.RED_LIGHT: "red light run:",
    InfractionKind.STOP_LINE: "stop line run:",
    InfractionKind.LANE_DEPARTURE: "lane departure:",
    InfractionKind.OFF_ROAD: "off the road:",
    InfractionKind.WRONG_WAY: "wrong way:",
}
_QUIET = frozenset({InfractionKind.LANE_DEPARTURE})


class DriveLog:
    """One InfractionWatch per ego, begun before the step it first takes part in and fed
    after every step; what they find is logged."""

    def __init__(self) -> None:
        self._watches: dict[int, InfractionWatch] = {}
        self._last: dict[int, Sample] = {}
        self._time = -math.inf

    def on(self, pipeline: TickPipeline[BridgeContext]) -> TickPipeline[BridgeContext]:
        """`pipeline` with this log's two stages around its world step."""
        return pipeline.with_stage(Stage("drive log start", self.begin), before="world").with_stage(
            Stage("drive log", self.run), after="world"
        )

    def begin(self, context: BridgeContext, tick: Tick) -> None:
        """Begin the watch of every ego that has none, from its sample before the step."""
        world = context.world
        for index, ego in enumerate(world.egos):
            watch = self._watches.get(ego.unique_id)
            if watch is None or watch.ego_index != index:
                self._watch(world, index, ego.unique_id, ego_sample(world, index))

    def run(self, context: BridgeContext, tick: Tick) -> None:
        world = context.world
        if world.sim_time == self._time:  # paused: nothing moved
            return
        self._time = world.sim_time
        present = set()
        for index, ego in enumerate(world.egos):
            unique_id = ego.unique_id
            present.add(unique_id)
            sample = ego_sample(world, index)
            watch = self._watches.get(unique_id)
            last = self._last.get(unique_id)
            if watch is None or watch.ego_index != index or _jumped(last, sample):
                watch = self._watch(world, index, unique_id, sample)
                continue
            self._last[unique_id] = sample
            for infraction in watch.observe(world, sample):
                _log(unique_id, infraction, sample)
        for gone in set(self._watches) - present:
            del self._watches[gone]
            del self._last[gone]

    def _watch(self, world: World, index: int, unique_id: int, sample: Sample) -> InfractionWatch:
        """A new watch of ego `index`, its first sample `sample` (where its rules start)."""
        watch = self._watches[unique_id] = InfractionWatch(world, index, blocked_after_s=math.inf)
        self._last[unique_id] = sample
        for infraction in watch.observe(world, sample):
            _log(unique_id, infraction, sample)
        return watch


def drive_log() -> DriveLog | None:
    """The drive log, or None when its lines would not be shown."""
    return DriveLog() if log.isEnabledFor(logging.INFO) else None


def _jumped(last: Sample | None, sample: Sample) -> bool:
    if last is None:
        return False
    speed = max(abs(last.speed_mps), abs(sample.speed_mps))
    reach = speed * max(sample.time_s - last.time_s, 0.0)
    return math.hypot(sample.x - last.x, sample.y - last.y) > reach + JUMP_M


def _log(ego_id: int, infraction: Infraction, sample: Sample) -> None:
    level = logging.DEBUG if infraction.kind in _QUIET else logging.INFO
    collision = infraction.kind in COLLISION_KINDS and infraction.magnitude is not None
    speed = infraction.magnitude if collision else sample.speed_mps
    log.log(
        level,
        "ego %d: %s %s at (%.1f, %.1f) m, t %.2f s, %s %.1f m/s",
        ego_id,
        _LABELS.get(infraction.kind, infraction.kind.value),
        infraction.detail,
        infraction.x,
        infraction.y,
        infraction.time_s,
        "impact at" if collision else "ego at",
        speed,
    )
