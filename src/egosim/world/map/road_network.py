"""Builds a LaneMap from roads (reference polylines) and the junctions joining them.

A road's reference line runs between the two directions of travel. Forward lanes (along
the reference) lie to its right, backward lanes to its left: right-hand traffic. Lane k
is the k-th lane counted from the reference line.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from itertools import pairwise

import numpy as np

from egosim.world.arrays import FloatArray
from egosim.world.map.compass import compass
from egosim.world.map.errors import MapGeometryError
from egosim.world.map.georef import GeoReference
from egosim.world.map.lanes import (
    Crosswalk,
    IntersectionSite,
    Lane,
    LaneMap,
    Sidewalk,
    TrafficLightSite,
)
from egosim.world.map.light_type import LightType
from egosim.world.map.polyline import (
    connector_curve,
    offset_left,
    segment_headings,
    stations,
    trim,
)

# Junction approach layout, outward from the junction box edge: a crosswalk, then the stop line.
CROSSWALK_GAP_M = 0.5
CROSSWALK_WIDTH_M = 4.0
STOP_LINE_GAP_M = 1.0
# Crosswalks reach this far past the carriageway edge, onto the kerb.
CROSSWALK_OVERHANG_M = 3.0
# Signal heads stand beside the stop line, this far outside the carriageway, this high.
LIGHT_KERB_OFFSET_M = 1.0
LIGHT_HEIGHT_M = 5.0
# Turn angle (rad) below which a movement counts as straight on; above the U-turn limit,
# no connector is built.
STRAIGHT_LIMIT_RAD = math.radians(30.0)
U_TURN_LIMIT_RAD = math.radians(150.0)

LightTypeRule = Callable[[int, str, bool], LightType]
"""(junction id, approach arm label, approach can turn left) -> protocol trafficLightType."""


def standard_light_type(junction_id: int, arm: str, can_turn_left: bool) -> LightType:
    """A four-lamp head (R/Y/left arrow/G) where the approach may turn left, a plain R/Y/G
    head elsewhere."""
    return LightType.RYG_LEFT_GREEN if can_turn_left else LightType.RYG


@dataclass(frozen=True)
class JunctionSpec:
    id: int
    center: tuple[float, float]
    radius: float
    """Distance from the centre at which road lanes end and connectors begin, m."""
    protected_lefts: bool = False
    """Opposite approaches go together and their left turns get a phase of their own;
    else an approach with a left arrow goes alone, its through and left movements
    together."""


@dataclass(frozen=True)
class RoadSpec:
    id: int
    reference: FloatArray
    lanes_forward: int
    lanes_backward: int
    speed_limit: float
    start_junction: int | None = None
    end_junction: int | None = None


@dataclass
class _LaneDraft:
    id: str
    centerline: FloatArray
    width: float
    speed_limit: float
    is_junction: bool = False
    successors: list[str] = field(default_factory=list)
    predecessors: list[str] = field(default_factory=list)
    left_neighbor: str | None = None
    right_neighbor: str | None = None
    stop_line_s: float | None = None
    traffic_light_ids: tuple[str, ...] = ()

    def freeze(self) -> Lane:
        return Lane(
            id=self.id,
            centerline=self.centerline,
            widths=np.full(len(self.centerline), self.width),
            speed_limit=self.speed_limit,
            successors=tuple(self.successors),
            predecessors=tuple(self.predecessors),
            left_neighbor=self.left_neighbor,
            right_neighbor=self.right_neighbor,
            stop_line_s=self.stop_line_s,
            traffic_light_ids=self.traffic_light_ids,
            is_junction=self.is_junction,
        )


@dataclass
class _Arm:
    """One road end at a junction. Lane lists are ordered from the reference line out."""

    label: str
    direction: FloatArray
    speed_limit: float
    incoming: list[str]
    outgoing: list[str]


class RoadNetworkBuilder:
    def __init__(self, lane_width: float) -> None:
        self.lane_width = lane_width
        self._junctions: dict[int, JunctionSpec] = {}
        self._arms: dict[int, list[_Arm]] = {}
        self._lanes: dict[str, _LaneDraft] = {}
        self._road_lanes: dict[int, tuple[list[str], list[str]]] = {}

    def add_junction(self, junction: JunctionSpec) -> None:
        self._junctions[junction.id] = junction
        self._arms[junction.id] = []

    def add_road(self, road: RoadSpec) -> None:
        start_cut = self._radius(road.start_junction)
        end_cut = self._radius(road.end_junction)
        reference = trim(np.asarray(road.reference, dtype=np.float64), start_cut, end_cut)
        forward = self._add_direction(road, reference, road.lanes_forward, backward=False)
        backward = self._add_direction(road, reference, road.lanes_backward, backward=True)
        self._road_lanes[road.id] = (forward, backward)
        if road.start_junction is not None:
            out = reference[1] - reference[0]
            self._add_arm(road.start_junction, out, road.speed_limit, backward, forward)
        if road.end_junction is not None:
            out = reference[-2] - reference[-1]
            self._add_arm(road.end_junction, out, road.speed_limit, forward, backward)

    def link(self, road_a: int, road_b: int) -> None:
        """Road a's end continues as road b's start, lane k into lane k, no junction."""
        a_forward, a_backward = self._road_lanes[road_a]
        b_forward, b_backward = self._road_lanes[road_b]
        for source, target in (
            *zip(a_forward, b_forward, strict=True),
            *zip(b_backward, a_backward, strict=True),
        ):
            self._connect(source, target)

    def build(
        self,
        name: str,
        georef: GeoReference,
        light_type: LightTypeRule = standard_light_type,
        sidewalks: Sequence[Sidewalk] = (),
    ) -> LaneMap:
        lights: list[TrafficLightSite] = []
        intersections: list[IntersectionSite] = []
        crosswalks: list[Crosswalk] = []
        for junction in self._junctions.values():
            arms = sorted(self._arms[junction.id], key=_arm_angle)
            labels = [arm.label for arm in arms]
            if len(set(labels)) != len(labels):
                raise MapGeometryError(f"junction {junction.id} has two arms facing {labels}")
            junction_lights = []
            for arm in arms:
                can_turn_left = self._add_connectors(junction, arm, arms)
                if arm.incoming:
                    rule = light_type(junction.id, arm.label, can_turn_left)
                    junction_lights.append(self._add_light(junction, arm, rule))
                crosswalks.append(self._crosswalk(junction, arm))
            arrow_lights = {
                light.id for light in junction_lights if light.light_type.has_left_arrow
            }
            lights.extend(junction_lights)
            intersections.append(
                IntersectionSite(
                    id=junction.id,
                    center=junction.center,
                    light_ids=tuple(light.id for light in junction_lights),
                    approach_groups=_approach_groups(junction, arms, arrow_lights),
                )
            )
        return LaneMap(
            name=name,
            lanes=[draft.freeze() for draft in self._lanes.values()],
            traffic_lights=lights,
            intersections=intersections,
            crosswalks=crosswalks,
            sidewalks=sidewalks,
            georef=georef,
        )

    def _radius(self, junction_id: int | None) -> float:
        return 0.0 if junction_id is None else self._junctions[junction_id].radius

    def _add_direction(
        self, road: RoadSpec, reference: FloatArray, count: int, backward: bool
    ) -> list[str]:
        ids = []
        for k in range(1, count + 1):
            offset = (k - 0.5) * self.lane_width
            line = offset_left(reference, offset if backward else -offset)
            if backward:
                line = line[::-1]
            chord = line[-1] - line[0]
            lane_id = f"R{road.id}_{compass(*chord)}_{k}"
            self._lanes[lane_id] = _LaneDraft(
                id=lane_id,
                centerline=np.column_stack((line, np.zeros(len(line)))),
                width=self.lane_width,
                speed_limit=road.speed_limit,
            )
            ids.append(lane_id)
        for inner, outer in pairwise(ids):
            self._lanes[inner].right_neighbor = outer
            self._lanes[outer].left_neighbor = inner
        return ids

    def _add_arm(
        self,
        junction_id: int,
        outward: FloatArray,
        speed_limit: float,
        incoming: list[str],
        outgoing: list[str],
    ) -> None:
        direction = outward / np.hypot(*outward)
        self._arms[junction_id].append(
            _Arm(compass(*direction), direction, speed_limit, incoming, outgoing)
        )

    def _connect(self, source: str, target: str) -> None:
        self._lanes[source].successors.append(target)
        self._lanes[target].predecessors.append(source)

    def _add_connectors(self, junction: JunctionSpec, arm: _Arm, arms: list[_Arm]) -> bool:
        """Straight, left and right connectors from one approach; True if it can turn left."""
        can_turn_left = False
        for exit_arm in arms:
            if exit_arm is arm or not exit_arm.outgoing or not arm.incoming:
                continue
            # Travel heading in = -arm direction, out = exit direction.
            turn = math.remainder(_angle(exit_arm.direction) - _angle(-arm.direction), math.tau)
            if abs(turn) > U_TURN_LIMIT_RAD:
                continue
            if abs(turn) < STRAIGHT_LIMIT_RAD:
                kind = "straight"
                pairs = list(zip(arm.incoming, exit_arm.outgoing, strict=False))
            elif turn > 0:
                kind, can_turn_left = "left", True
                pairs = [(arm.incoming[0], exit_arm.outgoing[0])]
            else:
                kind = "right"
                pairs = [(arm.incoming[-1], exit_arm.outgoing[-1])]
            for k, (source, target) in enumerate(pairs, start=1):
                self._add_connector(
                    f"J{junction.id}_{arm.label}_{exit_arm.label}_{kind}_{k}",
                    source,
                    target,
                    min(arm.speed_limit, exit_arm.speed_limit),
                )
        return can_turn_left

    def _add_connector(self, lane_id: str, source: str, target: str, speed: float) -> None:
        a = self._lanes[source].centerline[:, :2]
        b = self._lanes[target].centerline[:, :2]
        curve = connector_curve(
            a[-1], float(segment_headings(a)[-1]), b[0], float(segment_headings(b)[0])
        )
        self._lanes[lane_id] = _LaneDraft(
            id=lane_id,
            centerline=np.column_stack((curve, np.zeros(len(curve)))),
            width=self.lane_width,
            speed_limit=speed,
            is_junction=True,
        )
        self._connect(source, lane_id)
        self._connect(lane_id, target)

    def _add_light(
        self, junction: JunctionSpec, arm: _Arm, light_type: LightType
    ) -> TrafficLightSite:
        light_id = f"TL{junction.id}_{arm.label}"
        setback = CROSSWALK_GAP_M + CROSSWALK_WIDTH_M + STOP_LINE_GAP_M
        for lane_id in arm.incoming:
            lane = self._lanes[lane_id]
            lane.stop_line_s = float(stations(lane.centerline)[-1]) - setback
            lane.traffic_light_ids = (light_id,)
        # Incoming traffic drives along -direction, so its right-hand kerb is on this side.
        kerb_side = np.array([-arm.direction[1], arm.direction[0]])
        kerb = len(arm.incoming) * self.lane_width + LIGHT_KERB_OFFSET_M
        spot = np.asarray(junction.center) + arm.direction * (junction.radius + setback)
        spot = spot + kerb_side * kerb
        return TrafficLightSite(
            id=light_id,
            position=(float(spot[0]), float(spot[1]), LIGHT_HEIGHT_M),
            heading=_angle(arm.direction),
            light_type=light_type,
            lane_ids=tuple(arm.incoming),
            intersection_id=junction.id,
        )

    def _crosswalk(self, junction: JunctionSpec, arm: _Arm) -> Crosswalk:
        across = np.array([-arm.direction[1], arm.direction[0]])
        middle = np.asarray(junction.center) + arm.direction * (
            junction.radius + CROSSWALK_GAP_M + CROSSWALK_WIDTH_M / 2
        )
        reach_in = len(arm.incoming) * self.lane_width + CROSSWALK_OVERHANG_M
        reach_out = len(arm.outgoing) * self.lane_width + CROSSWALK_OVERHANG_M
        start = middle - across * reach_out
        end = middle + across * reach_in
        return Crosswalk(
            id=f"CW{junction.id}_{arm.label}",
            start=(float(start[0]), float(start[1])),
            end=(float(end[0]), float(end[1])),
            width=CROSSWALK_WIDTH_M,
            intersection_id=junction.id,
        )


def _angle(v: FloatArray) -> float:
    return math.atan2(float(v[1]), float(v[0]))


def _arm_angle(arm: _Arm) -> float:
    return _angle(arm.direction) % math.tau


def _approach_groups(
    junction: JunctionSpec, arms: list[_Arm], arrow_lights: set[str]
) -> tuple[tuple[str, ...], ...]:
    """Lights of opposite arms (within 30°) share a group, others stand alone; without
    protected lefts, a pair with a left arrow splits into its two lights, each served alone
    (so neither's left turn meets the other's traffic)."""
    signalled = [arm for arm in arms if arm.incoming]
    groups: list[tuple[str, ...]] = []
    used: set[str] = set()
    for arm in signalled:
        if arm.label in used:
            continue
        partners = [
            other
            for other in signalled
            if other.label not in used
            and other is not arm
            and float(np.dot(arm.direction, other.direction)) < -math.cos(STRAIGHT_LIMIT_RAD)
        ]
        group = [arm, *partners[:1]]
        used.update(a.label for a in group)
        lights = tuple(f"TL{junction.id}_{a.label}" for a in group)
        if junction.protected_lefts or not arrow_lights.intersection(lights):
            groups.append(lights)
        else:
            groups.extend((light,) for light in lights)
    return tuple(groups)
