"""OpenDRIVE traffic lights -> signal heads governing stop lines, grouped into intersections.

A light placed at station s of a road (or referenced there by a <signalReference>) governs
the drivable lanes of that road's section at s that travel the way the signal's orientation
faces ("+": along +s, "-": against, "none": both), limited to its <validity> lane ranges.
The stop line sits at s on each such lane; a stop line within STOP_AT_START_M of a lane's
start moves to the end of the lanes leading into it (the stop line belongs to the lane that
ends at it). Several heads may govern one lane; its stop line is then the first a driver
reaches. Each controller is an approach group; a junction's controllers make one
intersection, in their `sequence` order.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field

import numpy as np

from egosim.world.map.errors import MapRecordError
from egosim.world.map.lanes import IntersectionSite, TrafficLightSite
from egosim.world.map.light_type import LightType
from egosim.world.map.opendrive.document import SOURCE, Document, Road, SignalRecord
from egosim.world.map.opendrive.light_types import light_type_of
from egosim.world.map.opendrive.reference_line import lateral_points, reference_poses
from egosim.world.map.opendrive.road_lanes import LaneKey, RoadLane, section_range
from egosim.world.map.polyline import stations

STOP_AT_START_M = 1.0
STOP_LINE_TOLERANCE_M = 0.5
"""Heads of one lane whose lines lie further apart than this are noted."""
_INTEGER = re.compile(r"-?\d+")

# An intersection before it is numbered: (junction id or None, centre or None, groups).
_Draft = tuple[str | None, tuple[float, float] | None, list[tuple[str, ...]]]


@dataclass
class _Head:
    id: str
    position: tuple[float, float, float]
    heading: float
    light_type: LightType
    lane_ids: list[str] = field(default_factory=list)


@dataclass
class StopLine:
    station: float
    light_ids: list[str]


def build_signals(
    document: Document,
    lanes: dict[LaneKey, RoadLane],
    predecessors: dict[str, list[str]],
    notes: list[str],
) -> tuple[list[TrafficLightSite], list[IntersectionSite], dict[str, StopLine]]:
    """Lights, intersections and the stop line of each governed lane (by lane id)."""
    heads = _heads(document, notes)
    by_id = {lane.id: lane for lane in lanes.values()}
    stop_lines: dict[str, StopLine] = {}
    for road in document.roads.values():
        for signal in road.signals:
            head = heads.get(signal.id)
            if head is None:
                continue
            for lane_id, station in _governed(road, signal, lanes, by_id, predecessors):
                line = stop_lines.setdefault(lane_id, StopLine(station, []))
                if head.id in line.light_ids:
                    continue
                if abs(station - line.station) > STOP_LINE_TOLERANCE_M:
                    notes.append(
                        f"lane {lane_id}: light {head.id} stands at s={station:.1f} m, "
                        f"the lane stops at its first line, s={min(station, line.station):.1f} m"
                    )
                line.station = min(line.station, station)
                line.light_ids.append(head.id)
                head.lane_ids.append(lane_id)
    lights, intersections = _intersections(document, heads, lanes, notes)
    return lights, intersections, stop_lines


def _heads(document: Document, notes: list[str]) -> dict[str, _Head]:
    heads = {}
    for road in document.roads.values():
        for signal in road.signals:
            if signal.is_reference or not signal.dynamic:
                continue
            light_type = light_type_of(signal.type, signal.subtype)
            if light_type is None:
                notes.append(
                    f"road {road.id}: signal {signal.id} (type {signal.type}) is not a "
                    "vehicle light, ignored"
                )
                continue
            pose = reference_poses(road, np.array([signal.s]))
            x, y = lateral_points(pose, signal.t)[0]
            z, heading = pose[0, 2], pose[0, 3]
            position = (float(x), float(y), float(z + signal.z_offset))
            # A head faces the traffic it governs.
            facing = heading if signal.orientation == "-" else heading + math.pi
            heads[signal.id] = _Head(
                signal.id, position, math.remainder(facing, math.tau), light_type
            )
    return heads


def _governed(
    road: Road,
    signal: SignalRecord,
    lanes: dict[LaneKey, RoadLane],
    by_id: dict[str, RoadLane],
    predecessors: dict[str, list[str]],
) -> list[tuple[str, float]]:
    section = max((k for k, sec in enumerate(road.sections) if sec.s <= signal.s + 1e-9), default=0)
    start, end = section_range(road, section)
    governed: list[tuple[str, float]] = []
    for lane in lanes.values():
        key = lane.key
        if key.road != road.id or key.section != section:
            continue
        if signal.orientation in ("+", "-") and lane.forward != (signal.orientation == "+"):
            continue
        if signal.valid_lanes and not any(
            min(a, b) <= key.lane <= max(a, b) for a, b in signal.valid_lanes
        ):
            continue
        s = min(max(signal.s, start), end)
        along = stations(lane.centerline)
        order = slice(None) if lane.forward else slice(None, None, -1)
        station = float(np.interp(s, lane.road_s[order], along[order]))
        if station < STOP_AT_START_M and predecessors.get(lane.id):
            governed.extend(
                (p, float(stations(by_id[p].centerline)[-1])) for p in predecessors[lane.id]
            )
        else:
            governed.append((lane.id, station))
    return governed


def _intersections(
    document: Document,
    heads: dict[str, _Head],
    lanes: dict[LaneKey, RoadLane],
    notes: list[str],
) -> tuple[list[TrafficLightSite], list[IntersectionSite]]:
    controlled: dict[str, str] = {}

    def group(controller_id: str) -> tuple[str, ...]:
        controller = document.controllers.get(controller_id)
        if controller is None:
            notes.append(f"controller {controller_id} is not defined, ignored")
            return ()
        members = []
        for signal_id in controller.signal_ids:
            if signal_id not in heads:
                continue
            if signal_id in controlled:
                raise MapRecordError(
                    SOURCE,
                    f"controller id={controller_id!r}",
                    f"signal {signal_id} is already in controller {controlled[signal_id]}",
                )
            controlled[signal_id] = controller_id
            members.append(signal_id)
        return tuple(members)

    numbered: list[_Draft] = []
    for junction in document.junctions.values():
        groups = [g for g in (group(c) for c in junction.controllers) if g]
        if groups:
            roads = junction.connecting_roads
            points = [lane.centerline[:, :2] for lane in lanes.values() if lane.key.road in roads]
            mean = np.concatenate(points).mean(axis=0) if points else None
            center = None if mean is None else (float(mean[0]), float(mean[1]))
            numbered.append((junction.id, center, groups))
    for controller_id in document.controllers:
        if not any(controller_id in j.controllers for j in document.junctions.values()):
            members = group(controller_id)
            if members:
                numbered.append((None, None, [members]))
    for head_id in heads:
        if head_id not in controlled:
            notes.append(f"signal {head_id} is in no controller, it runs alone")
            numbered.append((None, None, [(head_id,)]))
    return _sites(numbered, heads)


def _sites(
    numbered: list[_Draft], heads: dict[str, _Head]
) -> tuple[list[TrafficLightSite], list[IntersectionSite]]:
    junction_ids = [j for j, _, _ in numbered if j is not None]
    use_own = all(_INTEGER.fullmatch(j) for j in junction_ids) and len(
        {int(j) for j in junction_ids}
    ) == len(junction_ids)
    taken = {int(j) for j in junction_ids} if use_own else set()
    next_id = max(taken, default=0) + 1
    lights: list[TrafficLightSite] = []
    intersections: list[IntersectionSite] = []
    for junction_id, center, groups in numbered:
        if use_own and junction_id is not None:
            number = int(junction_id)
        else:
            number, next_id = next_id, next_id + 1
        light_ids = tuple(i for g in groups for i in g)
        xy = (
            center if center is not None else np.mean([heads[i].position[:2] for i in light_ids], 0)
        )
        intersections.append(
            IntersectionSite(number, (float(xy[0]), float(xy[1])), light_ids, tuple(groups))
        )
        lights.extend(
            TrafficLightSite(
                id=i,
                position=heads[i].position,
                heading=heads[i].heading,
                light_type=heads[i].light_type,
                lane_ids=tuple(heads[i].lane_ids),
                intersection_id=number,
            )
            for i in light_ids
        )
    return lights, intersections
