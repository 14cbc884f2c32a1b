"""The drive as it happens, on `egosim run`'s console: every collision of an ego (with
whom, where) and every infraction the evaluation's rules find (red lights and stop lines
run, driving the wrong way, leaving the road), logged at INFO as each begins. Lane
departures, which every lane change makes, go to DEBUG.

It is the "drive log" stage of the tick pipeline, right after the world's step, and is
left out when nothing would be shown (the log level is above INFO).
"""

from __future__ import annotations

import logging
import math

from ..bridge import BridgeContext, Stage, Tick
from ..evaluation import (
    COLLISION_KINDS,
    Infraction,
    InfractionKind,
    InfractionWatch,
    ego_sample,
)
from ..evaluation.rules import Sample

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
    """One InfractionWatch per ego, fed after every step; what they find is logged."""

    def __init__(self) -> None:
        self._watches: dict[int, InfractionWatch] = {}
        self._last: dict[int, Sample] = {}
        self._time = -math.inf

    def stage(self) -> Stage[BridgeContext]:
        return Stage("drive log", self.run)

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
                watch = self._watches[unique_id] = InfractionWatch(
                    world, index, blocked_after_s=math.inf
                )
            self._last[unique_id] = sample
            for infraction in watch.observe(world, sample):
                _log(unique_id, infraction, sample)
        for gone in set(self._watches) - present:
            del self._watches[gone]
            del self._last[gone]


def drive_log_stage() -> Stage[BridgeContext] | None:
    """The stage, or None when its lines would not be shown."""
    return DriveLog().stage() if log.isEnabledFor(logging.INFO) else None


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
