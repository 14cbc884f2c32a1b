"""A recorded drive against its map: lane errors, red lights run, which map it was on."""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass
from functools import partial

import numpy as np
import numpy.typing as npt

from egosim.evaluation import Infraction
from egosim.evaluation.rules import Sample, StopLineWatch
from egosim.world.arrays import FloatArray
from egosim.world.map import LaneMap
from egosim.world.signals import OFF

from .recorded_drive import RecordedDrive

LIGHT_STATE_MAX_AGE_S = 1.0
"""A light's last status older than this (the status row runs at 10 Hz) counts as unknown."""


@dataclass(frozen=True, eq=False)
class LaneErrors:
    """Per ego sample: the lane it drove along and its station on it (m), its signed
    distance from that lane's centre line (m, left positive) and its heading minus the
    lane's (rad, in [-pi, pi))."""

    lane_ids: tuple[str, ...]
    s: FloatArray
    lateral_m: FloatArray
    heading_error_rad: FloatArray


def lane_errors(lane_map: LaneMap, drive: RecordedDrive) -> LaneErrors:
    """Each sample projected onto the lane pointing its way (see LaneMap.project_many)."""
    projections = lane_map.project_many(drive.xy, drive.heading)
    error = np.remainder(drive.heading - projections.heading + math.pi, math.tau) - math.pi
    ids = tuple(projections.lane_ids[i] for i in projections.lane_index)
    return LaneErrors(ids, projections.s, projections.lateral, error)


def red_lights_run(lane_map: LaneMap, drive: RecordedDrive, errors: LaneErrors) -> list[Infraction]:
    """Stop lines crossed while their light showed red, by the evaluation's rule, with the
    light's aspect as /GetTrafficLightStatus last showed it (unknown: not counted)."""
    watch = StopLineWatch(lane_map)
    nearest = lane_map.project_many(drive.xy)
    states = iter(drive.light_states)
    upcoming = next(states, None)
    latest: dict[str, tuple[float, int]] = {}
    found: list[Infraction] = []
    for i, t in enumerate(drive.times_s.tolist()):
        while upcoming is not None and upcoming.time_s <= t:
            latest[upcoming.light_id] = (upcoming.time_s, upcoming.aspect)
            upcoming = next(states, None)
        aspects = {
            light: aspect
            for light, (seen, aspect) in latest.items()
            if t - seen <= LIGHT_STATE_MAX_AGE_S
        }
        lane = lane_map.lanes[errors.lane_ids[i]]
        s = float(errors.s[i])
        sample = Sample(
            time_s=t,
            x=float(drive.x[i]),
            y=float(drive.y[i]),
            yaw=float(drive.heading[i]),
            speed_mps=float(drive.speed_mps[i]),
            lane_id=lane.id,
            s=s,
            lateral_m=float(errors.lateral_m[i]),
            lane_width_m=float(np.interp(s, lane.stations, lane.widths)),
            body_width_m=0.0,
            nearest=nearest[i],
        )
        found.extend(watch.observe(sample, partial(_lit_or_off, aspects)))
    return found


def _lit_or_off(aspects: dict[str, int], light: str) -> int:
    return aspects.get(light, OFF)


def best_fitting_map(xy: npt.ArrayLike, candidates: Iterable[LaneMap]) -> LaneMap:
    """The candidate on whose lanes the points lie best (least median distance to the
    nearest lane centre line)."""
    points = np.asarray(xy, dtype=np.float64).reshape(-1, 2)
    return min(
        candidates,
        key=lambda lane_map: float(np.median(np.abs(lane_map.project_many(points).lateral))),
    )
