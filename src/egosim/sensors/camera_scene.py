"""What a camera sees that stands still, as triangles: a map's static scene.

Built once per map: terrain, every lane's road surface (following the centreline's
elevation), raised sidewalks, lane lines and stop lines (egosim.world.map.markings),
zebra crosswalks, and traffic-light poles and heads, with the lamps' geometry that each
frame colours (egosim.sensors.camera_frame_mesh adds what moves).

Paint is 2 cm above the asphalt and terrain 5 cm below it, so depth testing alone
orders the layers.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from egosim.sensors.camera_labels import SemanticClass
from egosim.sensors.camera_mesh import Detail, Mesh, MeshBuilder, add_boxes, flat_color, ribbon
from egosim.sensors.scene_tiles import COARSE_TOLERANCE_M, SceneTiles, tile_order
from egosim.world.arrays import FloatArray
from egosim.world.map import Crosswalk, LaneMap, TrafficLightSite
from egosim.world.map.light_type import LightType
from egosim.world.map.markings import (
    LineStyle,
    MarkingColor,
    MarkingKind,
    RoadMarking,
    lane_edges,
    map_markings,
)
from egosim.world.map.polyline import kept_vertices, offset_left
from egosim.world.signals.aspects import GREEN, GREEN_LEFT, RED, YELLOW

ASPHALT = (64, 64, 64)
TERRAIN = (96, 118, 72)
SIDEWALK = (150, 146, 140)
# Road paint is a slightly warm white, as real paint is: a hue JPEG's chroma noise cannot
# flip out of the H 0-30 band lane detectors use (a neutral grey's hue is undefined).
PAINT = {
    MarkingColor.WHITE: (248, 240, 222),
    MarkingColor.YELLOW: (245, 190, 20),
    MarkingColor.BLUE: (30, 90, 220),
}
POLE = (110, 110, 110)
HEAD = (25, 25, 25)

# Asphalt reaches this far past each lane's edge, so an edge line lies on the road.
SHOULDER_M = 0.5
PAINT_LIFT_M = 0.02
# A strip's edges may move this far when straight runs are merged (see _add_strip).
STRIP_TOLERANCE_M = 0.005
MIN_DASH_M = 0.01
TERRAIN_DROP_M = 0.05
TERRAIN_MARGIN_M = 500.0
SIDEWALK_WIDTH_M = 2.5
SIDEWALK_HEIGHT_M = 0.15
CROSSWALK_STRIPE_M = 0.5
# Traffic-light heads: lamps in a row (Korean heads are horizontal), this size, m.
LAMP_SIZE_M = 0.3
LAMP_PITCH_M = 0.38
HEAD_DEPTH_M = 0.3
HEAD_HEIGHT_M = 0.45
POLE_SIDE_M = 0.2
# Lamps left to right as the approaching driver sees them.
LAMP_ORDER: dict[int, tuple[int, ...]] = {
    LightType.RYG: (RED, YELLOW, GREEN),
    LightType.RYG_LEFT: (RED, YELLOW, GREEN_LEFT),
    LightType.RYG_LEFT_GREEN: (RED, YELLOW, GREEN_LEFT, GREEN),
    LightType.FLASHING_YELLOW: (YELLOW, YELLOW, YELLOW),
}


def _add_strip(
    builder: MeshBuilder,
    left: FloatArray,
    right: FloatArray,
    color: FloatArray,
    label: SemanticClass,
    width_m: float = math.inf,
) -> None:
    """The strip between two (N, 3) polylines at both levels of detail: within
    STRIP_TOLERANCE_M of its edges when fine, within COARSE_TOLERANCE_M when coarse,
    where a strip narrower than that is left out."""
    fine = kept_vertices((left, right), STRIP_TOLERANCE_M)
    fine_strip = ribbon(left[fine], right[fine])
    if width_m < COARSE_TOLERANCE_M:
        builder.add(fine_strip, color, label, detail=Detail.FINE)
        return
    # Simplifying the fine strip is cheaper and, with the fine level's own tolerance
    # taken off, keeps the coarse one within COARSE_TOLERANCE_M of the original.
    coarse = fine[kept_vertices((left[fine], right[fine]), COARSE_TOLERANCE_M - STRIP_TOLERANCE_M)]
    if np.array_equal(fine, coarse):
        builder.add(fine_strip, color, label, detail=Detail.BOTH)
        return
    builder.add(fine_strip, color, label, detail=Detail.FINE)
    builder.add(ribbon(left[coarse], right[coarse]), color, label, detail=Detail.COARSE)


def _offset(points: FloatArray, distance: float) -> FloatArray:
    """An (N, 3) polyline moved `distance` to its left, z kept."""
    return np.column_stack((offset_left(points[:, :2], distance), points[:, 2]))


def _pieces(points: FloatArray, length: float, gap: float) -> list[FloatArray]:
    """The dashes of a polyline: `length` of paint, then `gap`, from its start."""
    steps = np.hypot(*np.diff(points[:, :2], axis=0).T)
    station = np.concatenate(([0.0], np.cumsum(steps)))
    dashes = []
    start = 0.0
    while start < station[-1] - 1e-6:
        end = min(start + length, station[-1])
        if end - start < MIN_DASH_M:
            break
        inside = (station > start) & (station < end)
        at = np.array([start, *station[inside], end])
        dashes.append(np.column_stack([np.interp(at, station, points[:, k]) for k in range(3)]))
        start += length + gap
    return dashes


@dataclass(frozen=True, eq=False)
class StaticScene:
    """A map's fixed geometry. `origin` (map, m) is subtracted from every vertex so that
    float32 keeps centimetres on maps kilometres wide; the mesh is stored tile after
    tile (`tiles`), so a renderer can skip what its camera cannot see."""

    origin: FloatArray
    mesh: Mesh
    tiles: SceneTiles
    lights: tuple[TrafficLightSite, ...]
    lamps: LampGeometry


def build_static_scene(lane_map: LaneMap) -> StaticScene:
    xmin, ymin, xmax, ymax = lane_map.bounds()
    origin = np.array([(xmin + xmax) / 2.0, (ymin + ymax) / 2.0, 0.0])
    builder = MeshBuilder(origin)
    road_z = np.concatenate([lane.centerline[:, 2] for lane in lane_map.lanes.values()])
    _add_terrain(builder, (xmin, ymin, xmax, ymax), float(road_z.min()) - TERRAIN_DROP_M)
    for lane in lane_map.lanes.values():
        left, right = lane_edges(lane, SHOULDER_M)
        _add_strip(builder, left, right, flat_color(ASPHALT), SemanticClass.ROAD)
    for walk in lane_map.sidewalks.values():
        points = np.column_stack((walk.points, np.full(len(walk.points), SIDEWALK_HEIGHT_M)))
        half = SIDEWALK_WIDTH_M / 2.0
        _add_strip(
            builder,
            _offset(points, half),
            _offset(points, -half),
            flat_color(SIDEWALK),
            SemanticClass.SIDEWALK,
        )
    for marking in map_markings(lane_map):
        _add_marking(builder, marking)
    for crosswalk in lane_map.crosswalks.values():
        _add_crosswalk(builder, crosswalk, _height_near(lane_map, crosswalk))
    lights = tuple(lane_map.traffic_lights.values())
    _add_light_fixtures(builder, lights)
    mesh = builder.mesh()
    vertex_order, tiles = tile_order(mesh.positions, builder.triangle_details())
    return StaticScene(origin, mesh.reordered(vertex_order), tiles, lights, _lamp_geometry(lights))


def _add_terrain(builder: MeshBuilder, bounds: tuple[float, ...], z: float) -> None:
    xmin, ymin, xmax, ymax = bounds
    m = TERRAIN_MARGIN_M
    corners = np.array(
        [
            [xmin - m, ymin - m, z],
            [xmax + m, ymin - m, z],
            [xmax + m, ymax + m, z],
            [xmin - m, ymax + m, z],
        ]
    )
    triangles = corners[[0, 1, 2, 0, 2, 3]]
    builder.add(triangles, flat_color(TERRAIN), SemanticClass.TERRAIN)


def _add_marking(builder: MeshBuilder, marking: RoadMarking) -> None:
    points = marking.points + np.array([0.0, 0.0, PAINT_LIFT_M])
    label = (
        SemanticClass.STOP_LINE
        if marking.kind is MarkingKind.STOP_LINE
        else SemanticClass.LANE_MARKING
    )
    count = len(marking.lines)
    spacing = marking.width_m + marking.double_gap_m
    for k, style in enumerate(marking.lines):
        # Lines listed left to right, centred on the marking's polyline.
        centre = _offset(points, ((count - 1) / 2.0 - k) * spacing) if count > 1 else points
        pieces = (
            [centre]
            if style is LineStyle.SOLID
            else _pieces(centre, marking.dash_length_m, marking.dash_gap_m)
        )
        for piece in pieces:
            if len(piece) < 2:
                continue
            half = marking.width_m / 2.0
            _add_strip(
                builder,
                _offset(piece, half),
                _offset(piece, -half),
                flat_color(PAINT[marking.color]),
                label,
                marking.width_m,
            )


def _height_near(lane_map: LaneMap, crosswalk: Crosswalk) -> float:
    middle = (np.asarray(crosswalk.start) + np.asarray(crosswalk.end)) / 2.0
    found = lane_map.project(float(middle[0]), float(middle[1]))
    return lane_map.pose_at(found.lane_id, found.s)[2]


def _add_crosswalk(builder: MeshBuilder, crosswalk: Crosswalk, z: float) -> None:
    """Zebra stripes across the walking line, `width` long, every other half metre."""
    start, end = np.asarray(crosswalk.start, float), np.asarray(crosswalk.end, float)
    length = float(np.hypot(*(end - start)))
    if length <= 0.0:
        return
    along = (end - start) / length
    across = np.array([-along[1], along[0]]) * crosswalk.width / 2.0
    stripe_starts = np.arange(0.0, length - CROSSWALK_STRIPE_M / 2.0, 2 * CROSSWALK_STRIPE_M)
    lift = z + PAINT_LIFT_M
    for s in stripe_starts:
        a = start + along * s
        b = start + along * min(s + CROSSWALK_STRIPE_M, length)
        quad = np.array([a + across, a - across, b - across, b + across])
        corners = np.column_stack((quad, np.full(4, lift)))
        builder.add(
            corners[[0, 1, 2, 0, 2, 3]],
            flat_color(PAINT[MarkingColor.WHITE]),
            SemanticClass.CROSSWALK,
        )


def _head_frame(site: TrafficLightSite) -> tuple[FloatArray, FloatArray, FloatArray]:
    """The head's centre, its facing direction and the driver's right, map frame."""
    facing = np.array([np.cos(site.heading), np.sin(site.heading), 0.0])
    right = np.array([-facing[1], facing[0], 0.0])
    return np.asarray(site.position, dtype=np.float64), facing, right


def _lamp_count(site: TrafficLightSite) -> int:
    return len(LAMP_ORDER.get(site.light_type, LAMP_ORDER[LightType.RYG]))


def _add_light_fixtures(builder: MeshBuilder, lights: Sequence[TrafficLightSite]) -> None:
    """Each light's dark head, and a pole from the ground up to it, just behind it (so the
    lamps stay in front)."""
    heads, poles = [], []
    for site in lights:
        centre, facing, _ = _head_frame(site)
        width = _lamp_count(site) * LAMP_PITCH_M + 0.1
        heads.append((*centre, HEAD_DEPTH_M, width, HEAD_HEIGHT_M, site.heading))
        top = centre[2] + HEAD_HEIGHT_M / 2.0
        foot = centre - facing * (HEAD_DEPTH_M + POLE_SIDE_M) / 2.0
        poles.append((foot[0], foot[1], top / 2.0, POLE_SIDE_M, POLE_SIDE_M, top, site.heading))
    for boxes, colour, label in (
        (heads, HEAD, SemanticClass.TRAFFIC_LIGHT),
        (poles, POLE, SemanticClass.POLE),
    ):
        table = np.array(boxes, dtype=np.float64).reshape(-1, 7)
        add_boxes(builder, table[:, :3], table[:, 3:6], table[:, 6], colour, label)


def lamp_centres(site: TrafficLightSite) -> list[tuple[int, FloatArray]]:
    """(lamp bit, centre on the head's front face) of each lamp, left to right."""
    centre, facing, right = _head_frame(site)
    order = LAMP_ORDER.get(site.light_type, LAMP_ORDER[LightType.RYG])
    front = centre + facing * (HEAD_DEPTH_M / 2.0 + 0.01)
    first = -(len(order) - 1) / 2.0 * LAMP_PITCH_M
    return [(lamp, front + right * (first + k * LAMP_PITCH_M)) for k, lamp in enumerate(order)]


@dataclass(frozen=True, eq=False)
class LampGeometry:
    """Every lamp's triangles (N, 3, map frame), with per vertex the light (index into
    the scene's lights) and the lamp bit it shows; bit 0 marks an arrow lamp's dark face.
    Light k's lamps lie in the box lower[k]..upper[k] (map frame)."""

    triangles: FloatArray
    light_index: npt.NDArray[np.int64]
    lamp_bit: npt.NDArray[np.int64]
    lower: FloatArray
    upper: FloatArray


def _lamp_geometry(lights: Sequence[TrafficLightSite]) -> LampGeometry:
    triangles, light_index, lamp_bit = [], [], []

    def add(shape: FloatArray, light: int, bit: int) -> None:
        triangles.append(shape)
        light_index.append(np.full(len(shape), light))
        lamp_bit.append(np.full(len(shape), bit))

    up = np.array([0.0, 0.0, 1.0])
    for k, site in enumerate(lights):
        _, facing, right = _head_frame(site)
        for lamp, centre in lamp_centres(site):
            if lamp == GREEN_LEFT:
                add(_square(centre, right, up), k, 0)
                # The arrow a hair in front of its dark lamp.
                add(_arrow(centre, right, up) + facing * 0.005, k, lamp)
            else:
                add(_square(centre, right, up), k, lamp)
    if not triangles:
        none = np.empty((0, 3))
        return LampGeometry(none, np.empty(0, np.int64), np.empty(0, np.int64), none, none)
    points, owners = np.concatenate(triangles), np.concatenate(light_index)
    starts = np.flatnonzero(np.diff(owners, prepend=-1))
    return LampGeometry(
        points,
        owners,
        np.concatenate(lamp_bit),
        np.minimum.reduceat(points, starts),
        np.maximum.reduceat(points, starts),
    )


def _square(centre: FloatArray, right: FloatArray, up: FloatArray) -> FloatArray:
    h = LAMP_SIZE_M / 2.0
    quad = np.array(
        [
            centre - right * h - up * h,
            centre + right * h - up * h,
            centre + right * h + up * h,
            centre - right * h + up * h,
        ]
    )
    return quad[[0, 1, 2, 0, 2, 3]]


def _arrow(centre: FloatArray, right: FloatArray, up: FloatArray) -> FloatArray:
    """A left-pointing arrow filling most of a lamp: a head and a shaft."""
    h = LAMP_SIZE_M / 2.0
    tip, back = centre - right * 0.8 * h, centre - right * 0.1 * h
    head = np.array([tip, back - up * 0.6 * h, back + up * 0.6 * h])
    shaft_end = centre + right * 0.8 * h
    thick = up * 0.22 * h
    shaft = np.array([back - thick, shaft_end - thick, shaft_end + thick, back + thick])[
        [0, 1, 2, 0, 2, 3]
    ]
    return np.concatenate([head, shaft])
