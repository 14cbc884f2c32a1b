"""What a camera sees, as triangles: the map's static scene and each frame's moving parts.

The static scene is built once per map: terrain, every lane's road surface (following
the centreline's elevation), raised sidewalks, lane lines and stop lines
(egosim.world.map.markings), zebra crosswalks, and traffic-light poles and heads. A frame
adds the objects (vehicles as a body and a cabin, pedestrians and obstacles as boxes,
each of its real size) and the lamps of every head, lit in the colour of its aspect.

Colours are shaded once on the CPU by a fixed sun (Lambert plus ambient), so the same
state always gives the same triangles. Paint is 2 cm above the asphalt and terrain 5 cm
below it, so depth testing alone orders the layers.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from egosim.sensors.camera_labels import SEMANTIC_PALETTE, SemanticClass, instance_colors
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
from egosim.world.map.polyline import offset_left
from egosim.world.signals.aspects import GREEN, GREEN_LEFT, OFF, RED, YELLOW
from egosim.world.traffic.objects import ObjectTable, ObjectType

SUN_DIRECTION = np.array([0.4, 0.3, 1.0]) / np.linalg.norm([0.4, 0.3, 1.0])
AMBIENT = 0.55

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
LAMP_OFF = (45, 45, 45)
LAMP_ON = {RED: (255, 30, 20), YELLOW: (255, 190, 0), GREEN: (0, 220, 90), GREEN_LEFT: (0, 220, 90)}
PEDESTRIAN = (190, 110, 80)
OBSTACLE = (230, 120, 30)
VEHICLE_PAINTS = ((200, 30, 30), (40, 70, 160), (220, 220, 215), (30, 30, 30), (120, 125, 130))

# Asphalt reaches this far past each lane's edge, so an edge line lies on the road.
SHOULDER_M = 0.5
PAINT_LIFT_M = 0.02
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
# Vehicles: a body of the full footprint this share of the height, a narrower cabin above.
BODY_SHARE = 0.55
CABIN_LENGTH_SHARE = 0.55
CABIN_WIDTH_SHARE = 0.9

# The unit cube's 12 triangles, outward normals, as corner indices of (±1, ±1, ±1).
_CORNERS = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], float)
_FACES = (
    ((0, 1, 3, 2), (-1, 0, 0)),
    ((4, 6, 7, 5), (1, 0, 0)),
    ((0, 4, 5, 1), (0, -1, 0)),
    ((2, 3, 7, 6), (0, 1, 0)),
    ((0, 2, 6, 4), (0, 0, -1)),
    ((1, 5, 7, 3), (0, 0, 1)),
)
_CUBE_TRIANGLES = np.array(
    [
        [a, b, c]
        for quad, _ in _FACES
        for a, b, c in ((quad[0], quad[1], quad[2]), (quad[0], quad[2], quad[3]))
    ]
).reshape(-1)
_CUBE_NORMALS = np.repeat(np.array([n for _, n in _FACES], float), 6, axis=0)


@dataclass(frozen=True, eq=False)
class Mesh:
    """A triangle list: 3 consecutive vertices per triangle.

    positions (N, 3) float32 in the scene frame (the map frame moved by the scene's
    origin); colors (N, 3) uint8 shaded RGB; semantic (N, 3) uint8 class colours;
    instance (N, 3) uint8 instance colours.
    """

    positions: npt.NDArray[np.float32]
    colors: npt.NDArray[np.uint8]
    semantic: npt.NDArray[np.uint8]
    instance: npt.NDArray[np.uint8]

    def __len__(self) -> int:
        return len(self.positions)

    @classmethod
    def empty(cls) -> Mesh:
        return cls(
            np.empty((0, 3), np.float32),
            np.empty((0, 3), np.uint8),
            np.empty((0, 3), np.uint8),
            np.empty((0, 3), np.uint8),
        )


class _MeshBuilder:
    """Collects triangles with their colour, class and instance, in scene coordinates."""

    def __init__(self, origin: FloatArray) -> None:
        self._origin = origin
        self._parts: list[tuple[FloatArray, FloatArray, SemanticClass, npt.NDArray[np.int64]]] = []

    def add(
        self,
        triangles: FloatArray,
        colors: npt.ArrayLike,
        label: SemanticClass,
        instances: npt.ArrayLike = 0,
    ) -> None:
        """`triangles` (N, 3) map points; `colors` one RGB or (N, 3); instances one or (N,)."""
        if len(triangles) == 0:
            return
        count = len(triangles)
        shaded = np.broadcast_to(np.asarray(colors, dtype=np.float64), (count, 3))
        ids = np.broadcast_to(np.asarray(instances, dtype=np.int64), (count,))
        self._parts.append((triangles - self._origin, shaded, label, ids))

    def mesh(self) -> Mesh:
        if not self._parts:
            return Mesh.empty()
        positions = np.concatenate([p[0] for p in self._parts]).astype(np.float32)
        colors = np.concatenate([p[1] for p in self._parts])
        labels = np.concatenate([np.full(len(p[0]), int(p[2])) for p in self._parts])
        ids = np.concatenate([p[3] for p in self._parts])
        return Mesh(
            positions,
            np.clip(np.rint(colors), 0, 255).astype(np.uint8),
            SEMANTIC_PALETTE[labels],
            instance_colors(ids),
        )


def sunlight(normals: FloatArray) -> FloatArray:
    """(N,) brightness of surfaces with unit `normals` (N, 3): ambient plus Lambert."""
    light: FloatArray = AMBIENT + (1.0 - AMBIENT) * np.maximum(normals @ SUN_DIRECTION, 0.0)
    return light


def _flat(color: Sequence[int]) -> FloatArray:
    """A colour on an upward-facing surface."""
    return np.asarray(color, dtype=np.float64) * float(sunlight(np.array([[0.0, 0.0, 1.0]]))[0])


def ribbon(left: FloatArray, right: FloatArray) -> FloatArray:
    """Triangles (6 (N - 1), 3) of the strip between two (N, 3) polylines."""
    a, b, c, d = left[:-1], right[:-1], right[1:], left[1:]
    return np.stack([a, b, c, a, c, d], axis=1).reshape(-1, 3)


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


def _box_triangles(
    centres: FloatArray, sizes: FloatArray, yaws: FloatArray
) -> tuple[FloatArray, FloatArray]:
    """Triangles (36 N, 3) and their normals of upright boxes (centre, size L W H, yaw)."""
    cos, sin = np.cos(yaws), np.sin(yaws)
    corners = _CORNERS[_CUBE_TRIANGLES][None, :, :] * (sizes[:, None, :] / 2.0)
    x = cos[:, None] * corners[..., 0] - sin[:, None] * corners[..., 1]
    y = sin[:, None] * corners[..., 0] + cos[:, None] * corners[..., 1]
    points = np.stack([x, y, corners[..., 2]], axis=-1) + centres[:, None, :]
    nx = cos[:, None] * _CUBE_NORMALS[None, :, 0] - sin[:, None] * _CUBE_NORMALS[None, :, 1]
    ny = sin[:, None] * _CUBE_NORMALS[None, :, 0] + cos[:, None] * _CUBE_NORMALS[None, :, 1]
    nz = np.broadcast_to(_CUBE_NORMALS[None, :, 2], nx.shape)
    normals = np.stack([nx, ny, nz], axis=-1)
    return points.reshape(-1, 3), normals.reshape(-1, 3)


def _add_boxes(
    builder: _MeshBuilder,
    centres: FloatArray,
    sizes: FloatArray,
    yaws: FloatArray,
    colors: npt.ArrayLike,
    label: SemanticClass,
    instances: npt.ArrayLike = 0,
) -> None:
    """Boxes shaded per face; colors (N, 3) or one; instances (N,) or one."""
    if len(centres) == 0:
        return
    points, normals = _box_triangles(centres, sizes, yaws)
    base = np.repeat(np.broadcast_to(np.asarray(colors, float), (len(centres), 3)), 36, axis=0)
    light = sunlight(normals)
    ids = np.repeat(np.broadcast_to(np.asarray(instances, np.int64), (len(centres),)), 36)
    builder.add(points, base * light[:, None], label, ids)


@dataclass(frozen=True, eq=False)
class StaticScene:
    """A map's fixed geometry. `origin` (map, m) is subtracted from every vertex so that
    float32 keeps centimetres on maps kilometres wide."""

    origin: FloatArray
    mesh: Mesh
    lights: tuple[TrafficLightSite, ...]
    lamps: LampGeometry


def build_static_scene(lane_map: LaneMap) -> StaticScene:
    xmin, ymin, xmax, ymax = lane_map.bounds()
    origin = np.array([(xmin + xmax) / 2.0, (ymin + ymax) / 2.0, 0.0])
    builder = _MeshBuilder(origin)
    road_z = np.concatenate([lane.centerline[:, 2] for lane in lane_map.lanes.values()])
    _add_terrain(builder, (xmin, ymin, xmax, ymax), float(road_z.min()) - TERRAIN_DROP_M)
    for lane in lane_map.lanes.values():
        left, right = lane_edges(lane, SHOULDER_M)
        builder.add(ribbon(left, right), _flat(ASPHALT), SemanticClass.ROAD)
    for walk in lane_map.sidewalks.values():
        points = np.column_stack((walk.points, np.full(len(walk.points), SIDEWALK_HEIGHT_M)))
        half = SIDEWALK_WIDTH_M / 2.0
        builder.add(
            ribbon(_offset(points, half), _offset(points, -half)),
            _flat(SIDEWALK),
            SemanticClass.SIDEWALK,
        )
    for marking in map_markings(lane_map):
        _add_marking(builder, marking)
    for crosswalk in lane_map.crosswalks.values():
        _add_crosswalk(builder, crosswalk, _height_near(lane_map, crosswalk))
    lights = tuple(lane_map.traffic_lights.values())
    _add_light_fixtures(builder, lights)
    return StaticScene(origin, builder.mesh(), lights, _lamp_geometry(lights))


def _add_terrain(builder: _MeshBuilder, bounds: tuple[float, ...], z: float) -> None:
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
    builder.add(triangles, _flat(TERRAIN), SemanticClass.TERRAIN)


def _add_marking(builder: _MeshBuilder, marking: RoadMarking) -> None:
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
            builder.add(
                ribbon(_offset(piece, half), _offset(piece, -half)),
                _flat(PAINT[marking.color]),
                label,
            )


def _height_near(lane_map: LaneMap, crosswalk: Crosswalk) -> float:
    middle = (np.asarray(crosswalk.start) + np.asarray(crosswalk.end)) / 2.0
    found = lane_map.project(float(middle[0]), float(middle[1]))
    return lane_map.pose_at(found.lane_id, found.s)[2]


def _add_crosswalk(builder: _MeshBuilder, crosswalk: Crosswalk, z: float) -> None:
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
            corners[[0, 1, 2, 0, 2, 3]], _flat(PAINT[MarkingColor.WHITE]), SemanticClass.CROSSWALK
        )


def _head_frame(site: TrafficLightSite) -> tuple[FloatArray, FloatArray, FloatArray]:
    """The head's centre, its facing direction and the driver's right, map frame."""
    facing = np.array([np.cos(site.heading), np.sin(site.heading), 0.0])
    right = np.array([-facing[1], facing[0], 0.0])
    return np.asarray(site.position, dtype=np.float64), facing, right


def _lamp_count(site: TrafficLightSite) -> int:
    return len(LAMP_ORDER.get(site.light_type, LAMP_ORDER[LightType.RYG]))


def _add_light_fixtures(builder: _MeshBuilder, lights: Sequence[TrafficLightSite]) -> None:
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
        _add_boxes(builder, table[:, :3], table[:, 3:6], table[:, 6], colour, label)


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
    the scene's lights) and the lamp bit it shows; bit 0 marks an arrow lamp's dark face."""

    triangles: FloatArray
    light_index: npt.NDArray[np.int64]
    lamp_bit: npt.NDArray[np.int64]


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
        return LampGeometry(np.empty((0, 3)), np.empty(0, np.int64), np.empty(0, np.int64))
    return LampGeometry(
        np.concatenate(triangles), np.concatenate(light_index), np.concatenate(lamp_bit)
    )


def _add_lamps(builder: _MeshBuilder, lamps: LampGeometry, aspects: npt.ArrayLike) -> None:
    if len(lamps.triangles) == 0:
        return
    aspect = np.asarray(aspects, dtype=np.int64)[lamps.light_index]
    lit = (aspect != OFF) & ((aspect & lamps.lamp_bit) != 0)
    colors = np.empty((len(lit), 3))
    colors[:] = LAMP_OFF
    for bit, colour in LAMP_ON.items():
        colors[lit & (lamps.lamp_bit == bit)] = colour
    builder.add(lamps.triangles, colors, SemanticClass.TRAFFIC_LIGHT)


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


def build_frame_mesh(
    scene: StaticScene,
    objects: ObjectTable,
    aspects: npt.ArrayLike,
    hidden_ids: Iterable[int] = (),
) -> Mesh:
    """The moving part of a frame: every object but `hidden_ids`, and the lamps."""
    builder = _MeshBuilder(scene.origin)
    keep = ~np.isin(objects.unique_ids, np.fromiter(hidden_ids, dtype=np.int64))
    types = objects.object_types[keep]
    ids = objects.unique_ids[keep]
    positions = objects.positions[keep]
    sizes = objects.sizes[keep]
    yaws = objects.headings[keep]
    vehicle = (types == ObjectType.NPC_VEHICLE) | (types == ObjectType.EGO)
    _add_vehicles(builder, positions[vehicle], sizes[vehicle], yaws[vehicle], ids[vehicle])
    for kind, label, colour in (
        (ObjectType.PEDESTRIAN, SemanticClass.PEDESTRIAN, PEDESTRIAN),
        (ObjectType.OBSTACLE, SemanticClass.OBSTACLE, OBSTACLE),
    ):
        rows = types == kind
        centres = positions[rows] + np.column_stack(
            (np.zeros((rows.sum(), 2)), sizes[rows, 2] / 2.0)
        )
        _add_boxes(builder, centres, sizes[rows], yaws[rows], colour, label, ids[rows])
    _add_lamps(builder, scene.lamps, aspects)
    return builder.mesh()


def _add_vehicles(
    builder: _MeshBuilder,
    feet: FloatArray,
    sizes: FloatArray,
    yaws: FloatArray,
    ids: npt.NDArray[np.int64],
) -> None:
    if len(feet) == 0:
        return
    paints = np.array(VEHICLE_PAINTS, dtype=np.float64)[ids % len(VEHICLE_PAINTS)]
    body = sizes * np.array([1.0, 1.0, BODY_SHARE])
    body_centres = feet + np.column_stack((np.zeros((len(feet), 2)), body[:, 2] / 2.0))
    _add_boxes(builder, body_centres, body, yaws, paints, SemanticClass.VEHICLE, ids)
    cabin = sizes * np.array([CABIN_LENGTH_SHARE, CABIN_WIDTH_SHARE, 1.0 - BODY_SHARE])
    cabin_centres = feet + np.column_stack(
        (np.zeros((len(feet), 2)), body[:, 2] + cabin[:, 2] / 2.0)
    )
    glass = paints * 0.45
    _add_boxes(builder, cabin_centres, cabin, yaws, glass, SemanticClass.VEHICLE, ids)
