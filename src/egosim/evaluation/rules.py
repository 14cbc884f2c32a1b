"""Traffic rules watched sample by sample: stop lines (red lights, stop signs), lane and
road excursions, wrong-way driving, standing blocked."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, replace

from egosim.evaluation.infractions import Infraction, InfractionKind
from egosim.evaluation.lane_travel import way_between
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
    A crossing is found on the way along the lanes between two samples (lane_travel), so
    a line passed between samples counts however far apart they are; it is timed where
    the way reaches the line, as if the ego drove the way at an even pace."""

    def __init__(self, lane_map: LaneMap) -> None:
        self._map = lane_map
        self._previous: Sample | None = None
        self._stood_at: str | None = None
        """The lane in whose stop zone the ego has stood since it last crossed a line."""

    def observe(self, sample: Sample, aspect_of: Callable[[str], int]) -> list[Infraction]:
        """The infractions between the previous sample and this one; `aspect_of` gives a
        light's aspect (protocol bits; OFF when unknown)."""
        previous, self._previous = self._previous, sample
        if self._stands_in_stop_zone(sample):
            self._stood_at = sample.lane_id
        found = [] if previous is None else self._crossings(previous, sample, aspect_of)
        if self._stood_at != sample.lane_id:  # it left that lane (past its line, or aside)
            self._stood_at = None
        return found

    def _stands_in_stop_zone(self, sample: Sample) -> bool:
        stop = _stop_station(self._map.lanes[sample.lane_id])
        return (
            stop is not None
            and sample.speed_mps < STOPPED_SPEED_MPS
            and 0.0 <= stop - sample.s <= STOP_ZONE_M
        )

    def _crossings(
        self, previous: Sample, sample: Sample, aspect_of: Callable[[str], int]
    ) -> list[Infraction]:
        chord = math.hypot(sample.x - previous.x, sample.y - previous.y)
        way = way_between(
            self._map, (previous.lane_id, previous.s), (sample.lane_id, sample.s), chord
        )
        if way is None:
            return []
        found = []
        for stretch in way.stretches:
            lane = self._map.lanes[stretch.lane_id]
            line = _stop_station(lane)
            if line is None or not stretch.start_s < line <= stretch.end_s:
                continue
            stood = self._stood_at == lane.id
            if stood:
                self._stood_at = None
            share = way.fraction_at(stretch, line)
            time_s = previous.time_s + share * (sample.time_s - previous.time_s)
            if (event := _crossing(self._map, lane, line, time_s, aspect_of, stood)) is not None:
                found.append(event)
        return found


def _crossing(
    lane_map: LaneMap,
    lane: Lane,
    line: float,
    time_s: float,
    aspect_of: Callable[[str], int],
    stood: bool,
) -> Infraction | None:
    """What crossing `lane`'s stop line at `time_s` was: a red light run, a stop sign run,
    or nothing wrong."""
    x, y, _, _ = lane_map.pose_at(lane.id, line)
    heads = lane.traffic_light_ids
    if heads:
        if is_red(combined_aspect(aspect_of(i) for i in heads)):
            detail = f"light {'/'.join(heads)} red at the stop line of lane {lane.id}"
            return Infraction(InfractionKind.RED_LIGHT, time_s, x, y, detail)
        return None
    if not stood:
        detail = f"did not stop at the stop line of lane {lane.id}"
        return Infraction(InfractionKind.STOP_LINE, time_s, x, y, detail)
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
