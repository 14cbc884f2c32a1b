"""The map's lanes as flat arrays indexed like LaneMap.lane_ids, for vectorised agents."""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from egosim.world.arrays import FloatArray, IntArray
from egosim.world.map import Lane, LaneMap
from egosim.world.map.polyline import segment_headings

# A junction lane turning more than this is a left (positive) or right (negative) turn.
TURN_LIMIT_RAD = math.radians(30.0)
TURN_LEFT, TURN_STRAIGHT, TURN_RIGHT = 1, 0, -1
COMFORT_LATERAL_ACCEL_MPS2 = 3.0
"""Lateral acceleration an NPC accepts in a curve; caps its speed at sqrt(a / curvature)."""
MAPS_KEPT = 4
"""Maps whose lane table is kept (maps are immutable: a batch worker's cases reuse it)."""


class LaneGraph:
    """Lengths, speed limits, stop lines, signals, turn directions and successors per lane."""

    def __init__(self, lane_map: LaneMap, lane_signals: IntArray) -> None:
        """`lane_signals`: per lane, the signal its drivers obey (LaneSignals.of_lane)."""
        self.lane_map = lane_map
        lanes = lane_table(lane_map)
        self.length = lanes.length
        self.speed_limit = lanes.speed_limit
        self.stop_s = lanes.stop_s
        self.light: IntArray = lane_signals
        """Per lane: its signal (an index into LightsView), -1 without a light."""
        self.curve_speed = lanes.curve_speed
        """Speed (m/s) an NPC drives at most on each lane: limit and curvature."""
        self.is_junction = lanes.is_junction
        self.turn = lanes.turn
        self.successors = lanes.successors

    def __len__(self) -> int:
        return len(self.length)


@dataclass(frozen=True)
class LaneTable:
    """What LaneGraph takes from the map alone, read-only: the same for every world on
    the map (a batch worker's cases on one map share it)."""

    length: FloatArray
    speed_limit: FloatArray
    stop_s: FloatArray
    curve_speed: FloatArray
    is_junction: npt.NDArray[np.bool_]
    turn: IntArray
    successors: tuple[tuple[int, ...], ...]


@functools.lru_cache(maxsize=MAPS_KEPT)
def lane_table(lane_map: LaneMap) -> LaneTable:
    """The lane table of `lane_map`, worked out once per map object."""
    lanes = [lane_map.lanes[i] for i in lane_map.lane_ids]
    speed_limit = np.array([lane.speed_limit for lane in lanes])
    table = LaneTable(
        length=np.array([lane.length for lane in lanes]),
        speed_limit=speed_limit,
        stop_s=np.array([np.nan if ln.stop_line_s is None else ln.stop_line_s for ln in lanes]),
        curve_speed=np.minimum(speed_limit, [_comfortable_curve_speed(lane) for lane in lanes]),
        is_junction=np.array([lane.is_junction for lane in lanes], dtype=bool),
        turn=np.array([_turn_direction(lane) for lane in lanes], dtype=np.int64),
        successors=tuple(tuple(lane_map.lane_index(s) for s in lane.successors) for lane in lanes),
    )
    for array in (table.length, table.speed_limit, table.stop_s, table.curve_speed):
        array.flags.writeable = False
    table.is_junction.flags.writeable = False
    table.turn.flags.writeable = False
    return table


def _turn_direction(lane: Lane) -> int:
    if not lane.is_junction:
        return TURN_STRAIGHT
    headings = segment_headings(lane.centerline)
    turn = math.remainder(float(headings[-1] - headings[0]), math.tau)
    if turn > TURN_LIMIT_RAD:
        return TURN_LEFT
    if turn < -TURN_LIMIT_RAD:
        return TURN_RIGHT
    return TURN_STRAIGHT


def _comfortable_curve_speed(lane: Lane) -> float:
    headings = segment_headings(lane.centerline)
    if len(headings) < 2:
        return math.inf
    turn = np.abs(np.remainder(np.diff(headings) + math.pi, math.tau) - math.pi)
    step = np.diff(lane.stations)
    curvature = float(np.max(turn / (0.5 * (step[:-1] + step[1:]))))
    return math.sqrt(COMFORT_LATERAL_ACCEL_MPS2 / curvature) if curvature > 0 else math.inf
