"""The lanes of one OpenDRIVE road: centrelines, widths, travel direction and speed of
the drivable ones; sidewalk lanes as walkways along their centres.

Lane borders stack outward from the reference line shifted by the road's laneOffset:
right lanes (-1, -2, ...) towards -t, left lanes (1, 2, ...) towards +t, each as wide as its
width polynomial. With right-hand traffic (the road's `rule`, RHT by default) right lanes
travel along +s and left lanes against it; LHT swaps them.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from egosim.world.arrays import FloatArray
from egosim.world.map.lanes import Sidewalk
from egosim.world.map.markings import LANE_LINE_WIDTH_M, LineStyle, MarkingColor, RoadMarking
from egosim.world.map.opendrive.document import LaneRecord, Road, RoadMarkRecord
from egosim.world.map.opendrive.polynomials import evaluate as evaluate_cubics
from egosim.world.map.opendrive.reference_line import (
    lateral_points,
    reference_poses,
    sample_stations,
)

DRIVABLE_LANE_TYPES = frozenset({"driving", "entry", "exit", "onRamp", "offRamp", "connectingRamp"})
SIDEWALK_LANE_TYPE = "sidewalk"
SAMPLE_STEP_M = 1.0
DEFAULT_SPEED_LIMIT_MPS = 50.0 / 3.6
# Lanes that open from or close to nothing keep this width where their polynomial reaches 0.
MIN_LANE_WIDTH_M = 0.05
_SAME_POINT_M = 1e-6
# <roadMark type>: its lines left to right; "none" paints nothing; other types (botts
# dots, grass, curb, custom) are reported and not drawn.
SOLID, DASHED = LineStyle.SOLID, LineStyle.DASHED
MARK_TYPES = {
    "solid": (SOLID,),
    "broken": (DASHED,),
    "solid solid": (SOLID, SOLID),
    "solid broken": (SOLID, DASHED),
    "broken solid": (DASHED, SOLID),
    "broken broken": (DASHED, DASHED),
}
MARK_COLORS = {
    "standard": MarkingColor.WHITE,
    "white": MarkingColor.WHITE,
    "yellow": MarkingColor.YELLOW,
    "blue": MarkingColor.BLUE,
}


@dataclass(frozen=True, order=True)
class LaneKey:
    road: str
    section: int
    lane: int


@dataclass(frozen=True)
class RoadLane:
    key: LaneKey
    id: str
    forward: bool
    """Travels along +s of its road."""
    road_s: FloatArray
    """Road station of each centreline point, in travel order."""
    centerline: FloatArray
    widths: FloatArray
    speed_limit: float
    in_junction: bool


def lane_id(key: LaneKey) -> str:
    return f"{key.road}_{key.section}_{key.lane}"


def section_range(road: Road, section: int) -> tuple[float, float]:
    end = road.sections[section + 1].s if section + 1 < len(road.sections) else road.length
    return road.sections[section].s, end


def travels_forward(road: Road, lane: int) -> bool:
    return (lane < 0) == (road.rule != "LHT")


def road_lanes(road: Road, notes: list[str]) -> tuple[list[RoadLane], list[Sidewalk]]:
    """The road's drivable lanes, and its sidewalk lanes as walkways along their centres."""
    stations = sample_stations(road, SAMPLE_STEP_M)
    lanes = []
    sidewalks = []
    for k, section in enumerate(road.sections):
        start, end = section_range(road, k)
        s = stations[(stations >= start - 1e-9) & (stations <= end + 1e-9)]
        if len(s) < 2:
            notes.append(f"road {road.id}: laneSection s={start:g} is too short to drive")
            continue
        poses = reference_poses(road, s)
        centres, widths = lateral_layout(road, section.lanes, s - start, s, notes)
        for record in section.lanes:
            walkway = record.type == SIDEWALK_LANE_TYPE
            if not (walkway or record.type in DRIVABLE_LANE_TYPES) or record.id not in centres:
                continue
            key = LaneKey(road.id, k, record.id)
            line = np.column_stack((lateral_points(poses, centres[record.id]), poses[:, 2]))
            if walkway:
                if np.max(widths[record.id]) > 0.0:
                    sidewalks.append(Sidewalk(lane_id(key), line))
                continue
            lane = _oriented(road, key, record, s, line, widths[record.id], start)
            if lane is not None:
                lanes.append(lane)
    return lanes, sidewalks


def road_markings(road: Road, notes: list[str]) -> list[RoadMarking]:
    """The paint of the road's <roadMark> records: on the centre lane's line and on each
    lane's outer border, one marking per record (to the next record or the section end)."""
    stations = sample_stations(road, SAMPLE_STEP_M)
    markings = []
    for k, section in enumerate(road.sections):
        start, end = section_range(road, k)
        s = stations[(stations >= start - 1e-9) & (stations <= end + 1e-9)]
        if len(s) < 2 or not (section.center_marks or any(r.road_marks for r in section.lanes)):
            continue
        poses = reference_poses(road, s)
        centres, widths = lateral_layout(road, section.lanes, s - start, s, [])
        borders = {0: evaluate_cubics(road.lane_offsets, s)}
        for lane_id, centre in centres.items():
            borders[lane_id] = centre + np.sign(lane_id) * widths[lane_id] / 2.0
        marked = [(0, section.center_marks), *((r.id, r.road_marks) for r in section.lanes)]
        for lane_id, marks in marked:
            for m, mark in enumerate(marks):
                if mark.type == "none":
                    continue
                mark_end = marks[m + 1].s_offset if m + 1 < len(marks) else end - start
                inside = (s - start >= mark.s_offset - 1e-9) & (s - start <= mark_end + 1e-9)
                if np.count_nonzero(inside) < 2:
                    continue  # a mark shorter than the sampling step
                painted = _marking(
                    f"{road.id}_{k}_{lane_id}_{m}", mark, poses[inside], borders[lane_id][inside]
                )
                if painted is None:
                    notes.append(
                        f"road {road.id}: roadMark type {mark.type!r} color {mark.color!r} "
                        "not drawn"
                    )
                else:
                    markings.append(painted)
    return markings


def _marking(
    marking_id: str, mark: RoadMarkRecord, poses: FloatArray, t: FloatArray
) -> RoadMarking | None:
    """The painted line of a roadMark, or None for a type or colour that is not drawn."""
    lines = MARK_TYPES.get(mark.type)
    color = MARK_COLORS.get(mark.color)
    if lines is None or color is None:
        return None
    points = np.column_stack((lateral_points(poses, t), poses[:, 2]))
    keep = np.concatenate(([True], np.hypot(*np.diff(points[:, :2], axis=0).T) > _SAME_POINT_M))
    if np.count_nonzero(keep) < 2:
        return None
    width = mark.width if mark.width is not None and mark.width > 0.0 else LANE_LINE_WIDTH_M
    return RoadMarking(marking_id, points[keep], color, lines, width_m=width)


def lateral_layout(
    road: Road,
    records: tuple[LaneRecord, ...],
    ds: FloatArray,
    s: FloatArray,
    notes: list[str],
) -> tuple[dict[int, FloatArray], dict[int, FloatArray]]:
    """Centre offset t and width of each lane at the stations."""
    offset = evaluate_cubics(road.lane_offsets, s)
    centres, widths = {}, {}
    for side in (-1, 1):
        border = offset.copy()
        for record in sorted((r for r in records if r.id * side > 0), key=lambda r: abs(r.id)):
            if record.has_border and not record.widths:
                notes.append(f"road {road.id}: lane {record.id} border records not read")
            width = evaluate_cubics(record.widths, ds)
            centres[record.id] = border + side * width / 2.0
            widths[record.id] = width
            border = border + side * width
    return centres, widths


def _oriented(
    road: Road,
    key: LaneKey,
    record: LaneRecord,
    s: FloatArray,
    line: FloatArray,
    width: FloatArray,
    section_start: float,
) -> RoadLane | None:
    if np.max(width) <= 0.0:
        return None
    forward = travels_forward(road, record.id)
    order = slice(None) if forward else slice(None, None, -1)
    line, s, width = line[order], s[order], width[order]
    step = np.hypot(*np.diff(line[:, :2], axis=0).T)
    keep = np.concatenate(([True], step > _SAME_POINT_M))
    if np.count_nonzero(keep) < 2:
        return None
    return RoadLane(
        key=key,
        id=lane_id(key),
        forward=forward,
        road_s=s[keep],
        centerline=line[keep],
        widths=np.maximum(width[keep], MIN_LANE_WIDTH_M),
        speed_limit=record.speed
        or _road_type_speed(road, section_start)
        or DEFAULT_SPEED_LIMIT_MPS,
        in_junction=road.in_junction,
    )


def _road_type_speed(road: Road, s: float) -> float | None:
    applying = [speed for start, speed in road.type_speeds if start <= s + 1e-9]
    return applying[-1] if applying else None
