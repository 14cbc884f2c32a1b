"""A LaneMap written out as MGeo: {file name: the JSON data that file holds}.

The inverse of build_mgeo_map, for maps egosim builds itself (the MGeo sample shipped
with the package, the benchmarks' large grids). MGeo ends a lane at its stop line, so a
lane whose stop line lies before its end is cut there and the rest is put in front of
the junction connectors it leads to. Lane boundaries carry the Korean road-marking codes
MGeo uses: 501 centre line (yellow, double solid), 503 lane line (white, broken), 505
edge line (white, solid).
"""

from __future__ import annotations

import math

import numpy as np

from egosim.world.arrays import FloatArray
from egosim.world.map.georef import GeoReference
from egosim.world.map.lanes import Lane, LaneMap
from egosim.world.map.light_type import LightType
from egosim.world.map.polyline import stations

SUB_TYPES = {
    LightType.RYG: ["red", "yellow", "straight"],
    LightType.RYG_LEFT: ["red", "yellow", "left"],
    LightType.RYG_LEFT_GREEN: ["red", "yellow", "left", "straight"],
    LightType.FLASHING_YELLOW: ["yellow"],
}
CENTRE_LINE = {"lane_type": 501, "lane_color": "yellow", "lane_shape": ["Solid", "Solid"]}
LANE_LINE = {"lane_type": 503, "lane_color": "white", "lane_shape": ["Broken"]}
EDGE_LINE = {"lane_type": 505, "lane_color": "white", "lane_shape": ["Solid"]}
CROSSWALK_SIGN = "5321"
_SAME_LINE_M = 0.05
"""Two lanes' boundaries closer than this (at their midpoints) are one painted line."""


def mgeo_files(lane_map: LaneMap, point_spacing_m: float = 1.0) -> dict[str, object]:
    """Every MGeo file of `lane_map`, centrelines resampled every `point_spacing_m`."""
    centrelines = _cut_at_stop_lines(lane_map)
    nodes = _NodeTable()
    junction_of = {lane.id: _nearest_junction(lane_map, lane) for lane in lane_map.lanes.values()}
    stop_nodes = set()
    for lane_id, points in centrelines.items():
        lane = lane_map.lanes[lane_id]
        junction = [junction_of[lane_id]] if lane.is_junction else []
        nodes.at(points[0], junction)
        end = nodes.at(points[-1], junction)
        if lane.stop_line_s is not None:
            stop_nodes.add(end)
    boundaries = _Boundaries(lane_map, point_spacing_m)
    links = [
        _link(lane_map.lanes[i], points, nodes, boundaries, point_spacing_m)
        for i, points in centrelines.items()
    ]
    return {
        "global_info.json": _global_info(lane_map.georef),
        "node_set.json": nodes.records(stop_nodes),
        "link_set.json": links,
        "lane_boundary_set.json": boundaries.records,
        "traffic_light_set.json": [
            {
                "idx": light.id,
                "point": list(light.position),
                "type": "car",
                "sub_type": SUB_TYPES.get(light.light_type, SUB_TYPES[LightType.RYG]),
                "link_id_list": list(light.lane_ids),
                "orientation": f"{math.degrees(light.heading) % 360.0:.1f}",
            }
            for light in lane_map.traffic_lights.values()
        ],
        "synced_traffic_light_set.json": [
            {
                "idx": f"SL{site.id}_{k}",
                "signal_id_list": list(group),
                "intersection_controller_id": f"IntTL{site.id}",
                "point": [*site.center, 0.0],
            }
            for site in lane_map.intersections.values()
            for k, group in enumerate(site.approach_groups)
        ],
        "intersection_controller_set.json": [
            {
                "idx": f"IntTL{site.id}",
                "point": [*site.center, 0.0],
                "synced_signal_id_list": [
                    f"SL{site.id}_{k}" for k in range(len(site.approach_groups))
                ],
            }
            for site in lane_map.intersections.values()
        ],
        "singlecrosswalk_set.json": [
            {
                "idx": walk.id,
                "points": _outline(walk.start, walk.end, walk.width),
                "sign_type": CROSSWALK_SIGN,
            }
            for walk in lane_map.crosswalks.values()
        ],
    }


def _global_info(georef: GeoReference) -> dict[str, object]:
    if georef.projection is not None:
        system = georef.projection
    else:
        system = f"UTM{georef.utm_zone}{'N' if georef.northern else 'S'}"
    return {
        "maj_ver": 2,
        "min_ver": 1,
        "global_coordinate_system": system,
        "local_origin_in_global": [georef.origin_east, georef.origin_north, georef.origin_up],
        "traffic_dir": "RHT",
    }


def _cut_at_stop_lines(lane_map: LaneMap) -> dict[str, FloatArray]:
    """Each lane's centreline, ending at its stop line; what lay past the line starts
    the lanes after it (each of which must then have that lane as its only predecessor)."""
    result = {lane_id: lane.centerline.copy() for lane_id, lane in lane_map.lanes.items()}
    for lane in lane_map.lanes.values():
        stop = lane.stop_line_s
        if stop is None or stop >= lane.length - 1e-3:
            continue
        head, tail = _split(lane.centerline, stop)
        followers = [lane_map.lanes[i] for i in lane.successors]
        if any(len(f.predecessors) != 1 for f in followers) or not followers:
            continue  # the stop line stays inside the lane (MGeo then puts it at the end)
        result[lane.id] = head
        for follower in followers:
            result[follower.id] = np.vstack((tail[:-1], result[follower.id]))
    return result


def _split(points: FloatArray, s: float) -> tuple[FloatArray, FloatArray]:
    along = stations(points)
    cut = np.array([np.interp(s, along, points[:, k]) for k in range(points.shape[1])])
    before = points[along < s]
    after = points[along > s]
    return np.vstack((before, cut)), np.vstack((cut, after))


def _resampled(points: FloatArray, spacing: float) -> FloatArray:
    along = stations(points)
    ts = np.unique(np.append(np.arange(0.0, along[-1], spacing), along[-1]))
    return np.column_stack([np.interp(ts, along, points[:, k]) for k in range(3)])


def _rounded(points: FloatArray) -> list[list[float]]:
    return [[round(float(v), 3) for v in point] for point in points]


def _nearest_junction(lane_map: LaneMap, lane: Lane) -> str:
    if not lane_map.intersections:
        return "J0"
    middle = lane.centerline[len(lane.centerline) // 2, :2]
    site = min(
        lane_map.intersections.values(),
        key=lambda site: float(np.hypot(*(middle - np.asarray(site.center)))),
    )
    return f"J{site.id}"


class _NodeTable:
    def __init__(self) -> None:
        self._ids: dict[tuple[float, float], str] = {}
        self._points: dict[str, FloatArray] = {}
        self._junctions: dict[str, set[str]] = {}

    def at(self, point: FloatArray, junctions: list[str]) -> str:
        key = (round(float(point[0]), 2), round(float(point[1]), 2))
        idx = self._ids.setdefault(key, f"N{len(self._ids):04d}")
        self._points.setdefault(idx, point)
        self._junctions.setdefault(idx, set()).update(junctions)
        return idx

    def records(self, stop_nodes: set[str]) -> list[dict[str, object]]:
        return [
            {
                "idx": idx,
                "point": _rounded(point[None])[0],
                "node_type": 1,
                "junction": sorted(self._junctions[idx]),
                "on_stop_line": idx in stop_nodes,
            }
            for idx, point in self._points.items()
        ]


class _Boundaries:
    """The painted lines beside the road lanes (junction connectors have none), each line
    shared by the two lanes it separates."""

    def __init__(self, lane_map: LaneMap, spacing: float) -> None:
        self.records: list[dict[str, object]] = []
        self.of_lane: dict[str, tuple[str, str]] = {}
        drawn: list[tuple[FloatArray, str]] = []
        for lane in lane_map.lanes.values():
            if lane.is_junction:
                continue
            # Along the whole road lane: the lines run on past a stop line to the junction.
            line = _resampled(lane.centerline, spacing)
            half = float(np.mean(lane.widths)) / 2.0
            sides = []
            for side, neighbour in ((1.0, lane.left_neighbor), (-1.0, lane.right_neighbor)):
                offset = _offset(line, side * half)
                known = _same_line(offset, drawn)
                if known is None:
                    known = self._add(offset, neighbour is not None, side > 0)
                    drawn.append((offset, known))
                sides.append(known)
            self.of_lane[lane.id] = (sides[0], sides[1])

    def _add(self, points: FloatArray, between_lanes: bool, left_side: bool) -> str:
        idx = f"B{len(self.records):04d}"
        kind = LANE_LINE if between_lanes else (CENTRE_LINE if left_side else EDGE_LINE)
        self.records.append(
            {
                "idx": idx,
                "points": _rounded(points),
                **kind,
                "lane_width": 0.15,
                "dash_interval_L1": 3.0 if kind is LANE_LINE else 0.0,
                "dash_interval_L2": 5.0 if kind is LANE_LINE else 0.0,
                "double_line_interval": 0.1 if kind is CENTRE_LINE else 0.0,
            }
        )
        return idx


def _offset(points: FloatArray, left_m: float) -> FloatArray:
    direction = np.gradient(points[:, :2], axis=0)
    direction /= np.maximum(np.linalg.norm(direction, axis=1, keepdims=True), 1e-12)
    normal = np.column_stack((-direction[:, 1], direction[:, 0]))
    result: FloatArray = points.copy()
    result[:, :2] += left_m * normal
    return result


def _same_line(points: FloatArray, drawn: list[tuple[FloatArray, str]]) -> str | None:
    """A line already drawn along these points (either way round)."""
    middle = points[len(points) // 2, :2]
    ends = {tuple(np.round(points[[0, -1], :2], 1).ravel())}
    for line, idx in drawn:
        close = np.hypot(*(line[len(line) // 2, :2] - middle)) < _SAME_LINE_M
        reverse = tuple(np.round(line[[-1, 0], :2], 1).ravel())
        same = tuple(np.round(line[[0, -1], :2], 1).ravel())
        if close and (reverse in ends or same in ends):
            return idx
    return None


def _link(
    lane: Lane,
    points: FloatArray,
    nodes: _NodeTable,
    boundaries: _Boundaries,
    spacing: float,
) -> dict[str, object]:
    marks = boundaries.of_lane.get(lane.id)
    width = float(np.mean(lane.widths))
    return {
        "idx": lane.id,
        "from_node_idx": nodes.at(points[0], []),
        "to_node_idx": nodes.at(points[-1], []),
        "points": _rounded(_resampled(points, spacing)),
        "max_speed": round(lane.speed_limit * 3.6),
        "link_type": "1",
        "road_id": lane.id.rsplit("_", 1)[0],
        "ego_lane": 1,
        "can_move_left_lane": lane.left_neighbor is not None,
        "can_move_right_lane": lane.right_neighbor is not None,
        "left_lane_change_dst_link_idx": lane.left_neighbor,
        "right_lane_change_dst_link_idx": lane.right_neighbor,
        "lane_ch_link_path": [],
        "related_signal": [],
        "lane_mark_left": [] if marks is None else [marks[0]],
        "lane_mark_right": [] if marks is None else [marks[1]],
        "width_start": round(width, 3),
        "width_end": round(width, 3),
        "force_width_start": False,
        "force_width_end": False,
    }


def _outline(
    start: tuple[float, float], end: tuple[float, float], width: float
) -> list[list[float]]:
    a, b = np.asarray(start), np.asarray(end)
    along = (b - a) / max(float(np.hypot(*(b - a))), 1e-12)
    side = np.array([-along[1], along[0]]) * width / 2.0
    corners = [a - side, b - side, b + side, a + side, a - side]
    return [[round(float(c[0]), 3), round(float(c[1]), 3), 0.0] for c in corners]
