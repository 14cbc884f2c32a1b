"""Traffic rules watched sample by sample: stop lines (red lights, stop signs), lane and
road excursions, wrong-way driving, standing blocked."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, replace

from egosim.evaluation.infractions import Infraction, InfractionKind
from egosim.world.map import Lane, LaneMap, LaneProjection
from egosim.world.signals import GREEN, GREEN_LEFT, OFF, RED, combined_aspect

STOPPED_SPEED_MPS = 0.1
"""Slower than this the ego counts as standing."""
STOP_ZONE_M = 5.0
"""At a stop sign, the ego must have stood within this distance before the stop line."""
WRONG_WAY_MIN_SPEED_MPS = 0.5
WRONG_WAY_ANGLE_RAD = math.pi / 2


def is_red(aspect: int) -> bool:
    """A light that stops every movement: red with no green lamp or arrow lit."""
    return aspect != OFF and bool(aspect & RED) and not aspect & (GREEN | GREEN_LEFT)


@dataclass(frozen=True)
class Sample:
    """What the rules look at in one sample of the drive (map frame, SI)."""

    time_s: float
    x: float
    y: float
    yaw: float
    speed_mps: float
    lane_id: str
    s: float
    lateral_m: float
    """Reference point from its lane's centre (the lane the ego is driving along)."""
    lane_width_m: float
    body_width_m: float
    nearest: LaneProjection | None
    """The nearest lane whatever its direction; None while the reference point is inside
    the lane it drives along (which is then on the road and the right way)."""


class StopLineWatch:
    """Reports crossing a stop line on red, or at a stop sign without having stopped.

    A stop line governed by several heads is red when the lamps lit on them together are
    (egosim.world.signals.lane_signals): a lit arrow on one head is a go for the line.
    """

    def __init__(self, lane_map: LaneMap) -> None:
        self._map = lane_map
        self._previous: Sample | None = None
        self._stood_at_line = False

    def watched_lights(self) -> tuple[str, ...]:
        """The heads of the stop line the next sample may cross: those of the lane of the
        last sample (the line may end that lane, so the next sample is on another)."""
        if self._previous is None:
            return ()
        return self._map.lanes[self._previous.lane_id].traffic_light_ids

    def observe(self, sample: Sample, aspect_of: Mapping[str, int]) -> Infraction | None:
        """`aspect_of`: the aspect of the watched lights (heads missing from it are not
        known and left out)."""
        previous, self._previous = self._previous, sample
        if previous is None:
            return None
        lane = self._map.lanes[previous.lane_id]
        stop = _stop_station(lane)
        if stop is None:
            return None
        on_lane = sample.lane_id == lane.id
        if on_lane and sample.s <= stop and stop - sample.s <= STOP_ZONE_M:
            self._stood_at_line |= sample.speed_mps < STOPPED_SPEED_MPS
        crossed = previous.s < stop and (
            (on_lane and sample.s >= stop) or sample.lane_id in lane.successors
        )
        stood = self._stood_at_line
        if crossed or not on_lane:
            self._stood_at_line = False
        if not crossed:
            return None
        x, y, _, _ = self._map.pose_at(lane.id, stop)
        heads = lane.traffic_light_ids
        if heads:
            if is_red(combined_aspect(aspect_of[i] for i in heads if i in aspect_of)):
                detail = f"light {'/'.join(heads)} red at the stop line of lane {lane.id}"
                return Infraction(InfractionKind.RED_LIGHT, sample.time_s, x, y, detail)
            return None
        if not stood:
            detail = f"did not stop at the stop line of lane {lane.id}"
            return Infraction(InfractionKind.STOP_LINE, sample.time_s, x, y, detail)
        return None


def _stop_station(lane: Lane) -> float | None:
    """Where a vehicle on `lane` must stop: its stop line, or its end under a light."""
    if lane.stop_line_s is not None:
        return lane.stop_line_s
    if lane.traffic_light_ids:
        return lane.length
    return None


class ExcursionWatch:
    """One infraction per excursion (a run of samples where a condition holds), placed
    where it began, its magnitude the largest amount seen during it."""

    def __init__(self, kind: InfractionKind) -> None:
        self.kind = kind
        self.records: list[Infraction] = []
        self._open = False

    def observe(self, sample: Sample, amount: float | None, detail: str = "") -> None:
        """`amount`: how far into the excursion the sample is, None when it is not in one."""
        if amount is None:
            self._open = False
            return
        if not self._open:
            self._open = True
            self.records.append(
                Infraction(self.kind, sample.time_s, sample.x, sample.y, detail, amount)
            )
            return
        last = self.records[-1]
        if last.magnitude is None or amount > last.magnitude:
            self.records[-1] = replace(last, magnitude=amount)


def lane_departure_m(sample: Sample, margin_m: float = 0.0) -> float | None:
    """How far the body reaches beyond its lane's boundary, None while it is inside."""
    beyond = abs(sample.lateral_m) + sample.body_width_m / 2.0 - sample.lane_width_m / 2.0
    return beyond if beyond > margin_m else None


def in_own_lane(lateral_m: float, lane_width_m: float) -> bool:
    return abs(lateral_m) <= lane_width_m / 2.0


def off_road_m(sample: Sample) -> float | None:
    """How far the reference point is outside the nearest lane, None while on a lane."""
    if sample.nearest is None:
        return None
    beyond = abs(sample.nearest.lateral) - sample.nearest.width / 2.0
    return beyond if beyond > 0.0 else None


def wrong_way(sample: Sample, lane_map: LaneMap) -> bool:
    """Moving against the lane it stands in (junction lanes, which cross, excepted)."""
    nearest = sample.nearest
    if nearest is None or sample.speed_mps < WRONG_WAY_MIN_SPEED_MPS:
        return False
    if off_road_m(sample) is not None or lane_map.lanes[nearest.lane_id].is_junction:
        return False
    turn = math.remainder(sample.yaw - nearest.heading, math.tau)
    return abs(turn) > WRONG_WAY_ANGLE_RAD


class BlockedWatch:
    """Reports standing still for longer than `limit_s`, once."""

    def __init__(self, limit_s: float) -> None:
        self.limit_s = limit_s
        self._since: float | None = None
        self.record: Infraction | None = None

    def observe(self, sample: Sample) -> Infraction | None:
        if sample.speed_mps >= STOPPED_SPEED_MPS:
            self._since = None
            return None
        if self._since is None:
            self._since = sample.time_s
        if self.record is None and sample.time_s - self._since > self.limit_s:
            detail = f"stood still for more than {self.limit_s:g} s"
            self.record = Infraction(
                InfractionKind.BLOCKED, sample.time_s, sample.x, sample.y, detail, self.limit_s
            )
            return self.record
        return None
