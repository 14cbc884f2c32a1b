"""/egosim/markers: the scene as visualization_msgs/MarkerArray for RViz, in frame `map`.

The map is built once and latched (Handlers.latched): roads at their width, lane centre
lines, stop lines, crosswalks, sidewalks, and the ids of road lanes and lights as text
(kept for the next run on the same map and start time: a batch worker builds it once).
At the row's rate (10 Hz) follow every ego, NPC, pedestrian and obstacle as a box and
every light as a sphere in the colour of its aspect; those markers live
LIFETIME_PERIODS of the row, so an object that leaves the scene leaves the display too.
Namespaces (`ns`) let RViz show or hide each layer.
"""

from __future__ import annotations

import functools
import math
from collections import defaultdict
from collections.abc import Iterable, Sequence
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from ...sensors.rotation import Quaternion, quaternion_from_euler
from ...world.map import LaneMap
from ...world.map.sections import lane_cross_section
from ...world.signals.aspects import shown_colour
from ...world.traffic import ObjectType
from ..context import MAP_FRAME, BridgeContext
from ..protocol.messages import header, point, quaternion, vector3
from ..protocol.table import Row

if TYPE_CHECKING:
    from ...msgs.typed import standard
    from ..protocol.releases import CanonicalProfile

LIFETIME_PERIODS = 5
"""Moving markers live this many periods of the row (0.5 s at 10 Hz): a missed message does
not blink, an object that is gone goes."""
UNTIMED_LIFETIME_S = 0.5
"""Their lifetime when the row has no rate."""
MAPS_KEPT = 4
"""Maps whose static scene message is kept (a batch worker's cases may use several)."""

# visualization_msgs/Marker types and actions.
CUBE, SPHERE_LIST, LINE_STRIP, LINE_LIST, TEXT_VIEW_FACING = 1, 7, 4, 5, 9
ADD = 0

RGBA = tuple[float, float, float, float]
ROAD: RGBA = (0.35, 0.35, 0.37, 1.0)
CENTRE_LINE: RGBA = (0.85, 0.85, 0.85, 0.8)
STOP_LINE: RGBA = (1.0, 1.0, 1.0, 1.0)
CROSSWALK: RGBA = (0.95, 0.95, 0.95, 0.6)
SIDEWALK: RGBA = (0.78, 0.72, 0.6, 1.0)
LANE_ID: RGBA = (0.6, 0.8, 1.0, 1.0)
LIGHT_ID: RGBA = (1.0, 0.7, 0.7, 1.0)
LIGHT_COLOURS: dict[str | None, RGBA] = {
    "red": (0.9, 0.1, 0.1, 1.0),
    "yellow": (1.0, 0.8, 0.0, 1.0),
    "green": (0.1, 0.85, 0.2, 1.0),
    None: (0.3, 0.3, 0.3, 1.0),
}
OBJECT_COLOURS: dict[int, RGBA] = {
    int(ObjectType.EGO): (0.1, 0.45, 1.0, 0.9),
    int(ObjectType.NPC_VEHICLE): (1.0, 0.55, 0.1, 0.9),
    int(ObjectType.PEDESTRIAN): (0.2, 0.9, 0.4, 0.9),
    int(ObjectType.OBSTACLE): (0.75, 0.75, 0.75, 0.9),
}
OBJECT_NAMESPACES = {
    int(ObjectType.EGO): "egos",
    int(ObjectType.NPC_VEHICLE): "npcs",
    int(ObjectType.PEDESTRIAN): "pedestrians",
    int(ObjectType.OBSTACLE): "obstacles",
}
CENTRE_LINE_WIDTH_M = 0.15
STOP_LINE_WIDTH_M = 0.4
SIDEWALK_WIDTH_M = 2.0
TEXT_HEIGHT_M = 1.5
LIGHT_SIZE_M = 1.0
# Layers stacked a few cm apart so RViz draws them in order, not flickering.
ROAD_Z_M, LINE_Z_M, TEXT_Z_M = -0.05, 0.02, 1.0


class _Builder:
    """Makes the Marker messages of one MarkerArray (message classes looked up once; one
    colour and one lifetime message per value, shared by the markers that have it)."""

    def __init__(self, profile: CanonicalProfile, header: standard.Header) -> None:
        self.profile = profile
        self.header = header
        self.marker_type = self.profile.message("visualization_msgs/Marker").make
        self.pose_type = self.profile.message("geometry_msgs/Pose").make
        self.point_type = self.profile.message("geometry_msgs/Point").make
        self.colour_type = self.profile.message("std_msgs/ColorRGBA").make
        self.duration_type = self.profile.message("builtin_interfaces/Duration").make
        self._colours: dict[RGBA, standard.ColorRGBA] = {}
        self._durations: dict[float, standard.Duration] = {}

    def colour(self, rgba: RGBA) -> standard.ColorRGBA:
        if (shared := self._colours.get(rgba)) is None:
            shared = self._colours[rgba] = self.colour_type(
                r=rgba[0], g=rgba[1], b=rgba[2], a=rgba[3]
            )
        return shared

    def points(
        self, xyz: Iterable[Sequence[float]] | npt.NDArray[np.float64]
    ) -> list[standard.Point]:
        rows = xyz.tolist() if isinstance(xyz, np.ndarray) else xyz
        return [self.point_type(x=float(x), y=float(y), z=float(z)) for x, y, z in rows]

    def new(
        self,
        ns: str,
        marker_id: int,
        marker_type: int,
        rgba: RGBA,
        scale: Sequence[float],
        *,
        position: Sequence[float] = (0.0, 0.0, 0.0),
        yaw: float = 0.0,
        lifetime_s: float = 0.0,
        points: list[standard.Point] | None = None,
        colors: list[standard.ColorRGBA] | None = None,
        text: str = "",
    ) -> standard.Marker:
        return self.marker_type(
            header=self.header,
            ns=ns,
            id=marker_id,
            type=marker_type,
            action=ADD,
            pose=self.pose_type(
                position=point(self.profile, position),
                orientation=quaternion(self.profile, yaw_quaternion(yaw)),
            ),
            scale=vector3(self.profile, scale),
            color=self.colour(rgba),
            lifetime=self._duration(lifetime_s),
            frame_locked=False,
            points=[] if points is None else points,
            colors=[] if colors is None else colors,
            text=text,
            mesh_resource="",
            mesh_use_embedded_materials=False,
        )

    def _duration(self, seconds: float) -> standard.Duration:
        if (shared := self._durations.get(seconds)) is None:
            sec, nanosec = _duration(seconds)
            shared = self._durations[seconds] = self.duration_type(sec=sec, nanosec=nanosec)
        return shared


def yaw_quaternion(yaw: float) -> Quaternion:
    """The orientation of a marker turned by `yaw`: most objects keep their heading from
    one message to the next (parked, stopped, driving straight), so it is worked out once
    per heading."""
    # -0.0 == 0.0, but their quaternions differ in the sign of z: the key tells them apart.
    return _yaw_quaternion(yaw, math.copysign(1.0, yaw))


@functools.lru_cache(maxsize=4096)
def _yaw_quaternion(yaw: float, sign: float) -> Quaternion:
    return quaternion_from_euler(0.0, 0.0, yaw)


def build_map_markers(context: BridgeContext, row: Row) -> bytes:
    """The static scene, once: roads, centre lines, stop lines, crosswalks, sidewalks, ids."""
    # A profile hashes by identity; its typed view (a Protocol) does not say so.
    return map_marker_bytes(context.world.map, context.profile, context.stamp_ns())  # type: ignore[arg-type]


@functools.lru_cache(maxsize=MAPS_KEPT)
def map_marker_bytes(lane_map: LaneMap, profile: CanonicalProfile, stamp_ns: int) -> bytes:
    """The static scene of `lane_map` stamped `stamp_ns`, serialised: the same bytes for the
    same map object (maps are immutable, and egosim.maps hands out the map it read before
    for the same source), built once for every run of a batch worker that starts at that
    time. Kept as bytes: the town's 1.3 MB of points take 12 ms to serialise each case."""
    message = map_markers(lane_map, profile, stamp_ns)
    return profile.message("visualization_msgs/MarkerArray").serialize(message)


def map_markers(
    lane_map: LaneMap, profile: CanonicalProfile, stamp_ns: int
) -> standard.MarkerArray:
    """The static scene of `lane_map` stamped `stamp_ns` as a message."""
    make = _Builder(profile, header(profile, stamp_ns, MAP_FRAME))
    # One point list per lane, shared by the road and centre-line markers (their poses set
    # their heights): points are most of the cost of this message.
    segments = {
        lane.id: make.points(_segments((lane.centerline,))) for lane in lane_map.lanes.values()
    }
    centre_lines = [point for points in segments.values() for point in points]
    markers = [
        *_roads(make, lane_map, segments),
        make.new(
            "lane_centres", 0, LINE_LIST, CENTRE_LINE, (CENTRE_LINE_WIDTH_M, 0.0, 0.0),
            position=(0.0, 0.0, LINE_Z_M), points=centre_lines,
        ),
    ]  # fmt: skip
    lift = np.array((0.0, 0.0, LINE_Z_M))
    stop_lines = [
        end
        for lane in lane_map.lanes.values() if lane.stop_line_s is not None
        for end in (lane_cross_section(lane_map, lane.id, lane.stop_line_s) + lift).tolist()
    ]  # fmt: skip
    if stop_lines:
        markers.append(
            make.new(
                "stop_lines", 0, LINE_LIST, STOP_LINE, (STOP_LINE_WIDTH_M, 0.0, 0.0),
                points=make.points(stop_lines),
            )
        )  # fmt: skip
    by_width: dict[float, list[tuple[float, float, float]]] = defaultdict(list)
    for crosswalk in lane_map.crosswalks.values():
        by_width[round(crosswalk.width, 2)] += [
            (*crosswalk.start, LINE_Z_M),
            (*crosswalk.end, LINE_Z_M),
        ]
    markers += [
        make.new("crosswalks", k, LINE_LIST, CROSSWALK, (width, 0.0, 0.0), points=make.points(ends))
        for k, (width, ends) in enumerate(sorted(by_width.items()))
    ]
    markers += [
        make.new(
            "sidewalks", k, LINE_STRIP, SIDEWALK, (SIDEWALK_WIDTH_M, 0.0, 0.0),
            points=make.points((x, y, LINE_Z_M) for x, y in sidewalk.points[:, :2]),
        )
        for k, sidewalk in enumerate(lane_map.sidewalks.values())
    ]  # fmt: skip
    road_lanes = [lane for lane in lane_map.lanes.values() if not lane.is_junction]
    for k, lane in enumerate(road_lanes):
        x, y, z, _ = lane_map.pose_at(lane.id, lane.length / 2.0)
        markers.append(
            make.new(
                "lane_ids", k, TEXT_VIEW_FACING, LANE_ID, (0.0, 0.0, TEXT_HEIGHT_M),
                position=(x, y, z + TEXT_Z_M), text=lane.id,
            )
        )  # fmt: skip
    for k, light in enumerate(lane_map.traffic_lights.values()):
        x, y, z = light.position
        markers.append(
            make.new(
                "light_ids", k, TEXT_VIEW_FACING, LIGHT_ID, (0.0, 0.0, TEXT_HEIGHT_M),
                position=(x, y, z + LIGHT_SIZE_M + TEXT_Z_M), text=light.id,
            )
        )  # fmt: skip
    return profile.message("visualization_msgs/MarkerArray").new(markers=markers)


def build_scene_markers(context: BridgeContext, row: Row) -> bytes:
    """What moves, at the row's rate: a box per object, a sphere per light. Its bytes,
    each marker from its parts: the header and namespace of its kind, then what the
    object says (id, pose, size), then what every marker of its kind has after that."""
    lifetime = LIFETIME_PERIODS / row.rate_hz if row.rate_hz else UNTIMED_LIFETIME_S
    profile = context.profile
    marker = profile.message("visualization_msgs/Marker")
    sec, nanosec = divmod(context.stamp_ns(), 1_000_000_000)
    head = marker.flat(last="ns").pack
    heads = {kind: head(0, sec, nanosec, MAP_FRAME, ns) for kind, ns in OBJECT_NAMESPACES.items()}
    box = marker.flat("id", "scale.z").pack
    objects = context.objects()
    markers = [
        b"".join((
            heads[kind],
            box(uid, CUBE, ADD, x, y, z + height / 2.0, *yaw_quaternion(heading),
                length, width, height),
            _unchanging_end(profile, OBJECT_COLOURS[kind], lifetime),  # type: ignore[arg-type]
        ))
        for uid, kind, (x, y, z), heading, (length, width, height) in zip(
            objects.unique_ids.tolist(),
            objects.object_types.tolist(),
            objects.positions.tolist(),
            objects.headings.tolist(),
            objects.sizes.tolist(),
            strict=True,
        )
    ]  # fmt: skip
    world = context.world
    signals = world.signals
    if len(signals.light_ids):
        lights_sec, lights_nanosec = _duration(lifetime)
        markers.append(
            marker.flat().pack(
                0, sec, nanosec, MAP_FRAME, "lights", 0, SPHERE_LIST, ADD,
                0.0, 0.0, 0.0, *yaw_quaternion(0.0), *(LIGHT_SIZE_M,) * 3,
                *LIGHT_COLOURS[None], lights_sec, lights_nanosec, False,
                # A profile hashes by identity; its typed view (a Protocol) does not say so.
                light_sites(profile, world.map, signals.light_ids),  # type: ignore[arg-type]
                light_colours(profile, tuple(signals.aspects().tolist())),  # type: ignore[arg-type]
                "", "", False,
            )
        )  # fmt: skip
    return profile.message("visualization_msgs/MarkerArray").flat().pack(markers)


@functools.lru_cache(maxsize=64)
def _unchanging_end(profile: CanonicalProfile, rgba: RGBA, lifetime_s: float) -> bytes:
    """A moving box's Marker bytes from its colour on: the same for every box of a kind."""
    marker = profile.message("visualization_msgs/Marker")
    end = marker.flat("color.r", "mesh_use_embedded_materials").pack
    return end(*rgba, *_duration(lifetime_s), False, [], [], "", "", False)


def _duration(seconds: float) -> tuple[int, int]:
    """A builtin_interfaces/Duration's sec and nanosec."""
    sec, nanosec = divmod(round(seconds * 1e9), 1_000_000_000)
    return sec, nanosec


@functools.lru_cache(maxsize=2)  # a map held here at most until the next run's
def light_sites(
    profile: CanonicalProfile, lane_map: LaneMap, light_ids: tuple[str, ...]
) -> tuple[bytes, ...]:
    """The lights' points of the lights marker (geometry_msgs/Point bytes): the map's,
    so made once."""
    sites = lane_map.traffic_lights
    pack = profile.message("geometry_msgs/Point").flat().pack
    return tuple(pack(*(float(v) for v in sites[i].position)) for i in light_ids)


@functools.lru_cache(maxsize=64)
def light_colours(profile: CanonicalProfile, aspects: tuple[int, ...]) -> tuple[bytes, ...]:
    """The lights' colours of the lights marker (std_msgs/ColorRGBA bytes), made again
    only when an aspect changes."""
    pack = profile.message("std_msgs/ColorRGBA").flat().pack
    made = {rgba: pack(*rgba) for rgba in LIGHT_COLOURS.values()}
    return tuple(made[LIGHT_COLOURS[shown_colour(aspect)]] for aspect in aspects)


def _roads(
    make: _Builder, lane_map: LaneMap, segments: dict[str, list[standard.Point]]
) -> list[standard.Marker]:
    """Every lane's centre line drawn as wide as the lane (one marker per width)."""
    by_width: dict[float, list[standard.Point]] = defaultdict(list)
    for lane in lane_map.lanes.values():
        by_width[round(float(np.mean(lane.widths)), 2)] += segments[lane.id]
    return [
        make.new(
            "roads", k, LINE_LIST, ROAD, (width, 0.0, 0.0),
            position=(0.0, 0.0, ROAD_Z_M), points=points,
        )
        for k, (width, points) in enumerate(sorted(by_width.items()))
    ]  # fmt: skip


def _segments(polylines: Iterable[npt.ArrayLike]) -> npt.NDArray[np.float64]:
    """(N, 3) polylines as LINE_LIST point pairs, each segment's two ends: (M, 3)."""
    pieces = []
    for line in polylines:
        points = np.asarray(line, dtype=np.float64)
        ends = np.empty((2 * (len(points) - 1), 3))
        ends[0::2], ends[1::2] = points[:-1], points[1:]
        pieces.append(ends)
    return np.concatenate(pieces) if pieces else np.zeros((0, 3))
