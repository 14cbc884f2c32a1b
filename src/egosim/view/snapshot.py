"""World -> plain data for the browser: the map once per client, then frames.

A frame is taken in two halves so the simulation loop pays as little as possible:
`capture_frame` runs on the loop thread between two steps and only copies numbers and
small arrays out of the world; `encode` runs on the server thread and turns them into
JSON (rounded to the centimetre / milliradian, arrays as flat lists). Everything stays
in SI units (m, s, rad, m/s): the page converts for display.
"""

from __future__ import annotations

import base64
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt
import orjson

from ..bridge import BridgeContext
from ..world import World
from ..world.arrays import FloatArray
from ..world.map import LaneMap
from ..world.map.markings import (
    LineStyle,
    MarkingKind,
    RoadMarking,
    lane_edges,
    map_markings,
)
from ..world.signals import OFF, RED
from ..world.signals.aspects import GREEN, GREEN_LEFT, YELLOW
from ..world.traffic import ObjectState, ObjectTable, ObjectType
from .messages import (
    CapturedFrame,
    Collision,
    EgoEntry,
    ImageSource,
    MapLane,
    MapMarking,
    MapMessage,
    Message,
    ObjectColumns,
    Point,
    Polyline,
    ReplayState,
    SensorImage,
)

#: How long a collision keeps flashing on the page, s of simulation time.
COLLISION_FLASH_S = 2.0
#: Decimal places sent for lengths (cm) and angles (mrad).
METRE_DIGITS = 2
RADIAN_DIGITS = 3


# -- the map -----------------------------------------------------------------------------


def _point(values: npt.ArrayLike) -> Point:
    """A point or any flat row of lengths, to the centimetre."""
    point: Point = np.round(np.asarray(values, dtype=np.float64), METRE_DIGITS).tolist()
    return point


def _polyline(points: npt.ArrayLike) -> Polyline:
    """(N, 2) points, to the centimetre."""
    polyline: Polyline = np.round(np.asarray(points, dtype=np.float64), METRE_DIGITS).tolist()
    return polyline


def _paint(marking: RoadMarking) -> MapMarking:
    """One marking as the page draws it: its points, colour and whether it is dashed."""
    dashed = LineStyle.DASHED in marking.lines
    return {
        "points": _polyline(marking.points[:, :2]),
        "style": "dashed" if dashed else "solid",
        "color": marking.color.value,
        "double": len(marking.lines) > 1,
    }


def map_snapshot(lane_map: LaneMap) -> MapMessage:
    """Everything static the page draws: lanes (as road surface outlines), the map's
    paint (the same markings the cameras see), junctions, crosswalks, sidewalks and the
    light heads."""
    lanes: list[MapLane] = []
    for lane in lane_map.lanes.values():
        left, right = lane_edges(lane)
        lanes.append(
            {
                "id": lane.id,
                "junction": lane.is_junction,
                "outline": _polyline(np.concatenate((left, right[::-1]))[:, :2]),
            }
        )
    paint = map_markings(lane_map)
    markings = [_paint(m) for m in paint if m.kind is MarkingKind.LANE_LINE]
    stop_lines = [_polyline(m.points[:, :2]) for m in paint if m.kind is MarkingKind.STOP_LINE]
    return {
        "type": "map",
        "name": lane_map.name,
        "bounds": _point(lane_map.bounds()),
        "lanes": lanes,
        "markings": markings,
        "stop_lines": stop_lines,
        "junctions": [
            {"id": site.id, "centre": _point(site.center)}
            for site in lane_map.intersections.values()
        ],
        "crosswalks": [
            {"id": c.id, "start": _point(c.start), "end": _point(c.end), "width": c.width}
            for c in lane_map.crosswalks.values()
        ],
        "sidewalks": [_polyline(s.points[:, :2]) for s in lane_map.sidewalks.values()],
        "lights": [
            {
                "id": light.id,
                "position": _point(light.position[:2]),
                "heading": round(light.heading, RADIAN_DIGITS),
                "type": light.light_type,
            }
            for light in lane_map.traffic_lights.values()
        ],
        "aspect_bits": {"red": RED, "yellow": YELLOW, "green": GREEN, "left": GREEN_LEFT},
        "aspect_off": OFF,
        "object_kinds": {kind.name.lower(): int(kind) for kind in ObjectType},
    }


# -- frames ------------------------------------------------------------------------------


@dataclass(frozen=True)
class FrameInfo:
    """What the app knows beside the world: clock mode, pace, ROS graph, control state."""

    clock_mode: str
    real_time_factor: float | None
    controls_enabled: bool


def ego_entries(context: BridgeContext) -> list[EgoEntry]:
    """Every ego as a frame lists it."""
    world = context.world
    egos: list[EgoEntry] = []
    for index, ego in enumerate(world.egos):
        status = world.ego_status(index)
        lane = world.ego_lane_state(index)
        model = ego.vehicle.model
        egos.append(
            {
                "id": ego.unique_id,
                "model": model.name,
                "x": status.pose.x,
                "y": status.pose.y,
                "yaw": status.pose.yaw,
                "length": model.length,
                "width": model.width,
                "centre_offset": model.bounding_box_center_offset,
                "speed": status.speed,
                "forward_speed": status.velocity[0],
                "acceleration": status.acceleration[0],
                "gear": status.gear.name.lower(),
                "ctrl_mode": int(context.ego_session(ego).ctrl_mode),
                "steer": status.front_steer,
                "accel_pedal": status.accel_pedal,
                "brake_pedal": status.brake_pedal,
                "lane_offset": lane.lateral_offset,
                "lane_id": lane.lane_id,
            }
        )
    return egos


def _collisions(world: World) -> list[Collision]:
    """Collisions of the last COLLISION_FLASH_S, newest first: when, and where the struck
    object stood (ego collisions) or the first vehicle of the pair (NPC collisions)."""
    since = world.sim_time - COLLISION_FLASH_S
    recent = []
    for entry in reversed(world.ego_collision_log):
        if entry.time_s < since:
            break
        recent.append(_collision_at(entry.time_s, entry.other))
    for pair in reversed(world.vehicle_collisions):
        if pair.time_s < since:
            break
        recent.append(_collision_at(pair.time_s, pair.vehicles[0]))
    return recent


def _collision_at(time_s: float, thing: ObjectState) -> Collision:
    return {"t": time_s, "x": thing.position[0], "y": thing.position[1]}


def _replay(context: BridgeContext) -> ReplayState | None:
    replay = context.replay
    if replay.timeline is None:
        return None
    return {
        "mode": replay.mode.name.lower(),
        "status": replay.playback_status.name.lower(),
        "position": replay.playback_time,
        "duration": replay.timeline.duration,
        "speed": replay.speed,
    }


def capture_frame(
    context: BridgeContext,
    info: FrameInfo,
    lidar: FloatArray | None = None,
    images: Sequence[ImageSource] = (),
) -> CapturedFrame:
    """The world now, as numbers and array copies (loop thread; see `encode`).

    `lidar`: LiDAR points (N, 2+) already in the map frame, or None when not shown.
    """
    world = context.world
    shown_images = [image for source in images if (image := source()) is not None]
    return {
        "type": "frame",
        "sim_time": world.sim_time,
        "paused": world.paused,
        "clock_mode": info.clock_mode,
        "real_time_factor": info.real_time_factor,
        "sync_frame": context.sync.frame if context.sync.holds_time else None,
        "controls": info.controls_enabled,
        "followed": context.session.camera_index,
        "egos": ego_entries(context),
        # The tables themselves: the world replaces, never edits, their arrays, so the
        # server thread may read them later (see _objects).
        "objects": world.shown_tables(),
        # In the order of the map's lights (both follow the map's light table).
        "light_aspects": world.signals.aspects().copy(),
        "collisions": _collisions(world),
        "replay": _replay(context),
        "lidar": None if lidar is None else lidar[:, :2].copy(),
        "images": shown_images,
    }


_ANGLE_KEYS = frozenset({"yaw", "steer"})


def _objects(tables: list[ObjectTable]) -> ObjectColumns:
    """NPCs, pedestrians and obstacles as columns (server thread)."""
    table = ObjectTable.concatenate(tables)
    return {
        "id": table.unique_ids,
        "kind": table.object_types,
        "x": table.positions[:, 0],
        "y": table.positions[:, 1],
        "yaw": table.headings,
        "length": table.sizes[:, 0],
        "width": table.sizes[:, 1],
        "speed": np.hypot(table.velocities[:, 0], table.velocities[:, 1]),
    }


def _plain(value: object, key: str = "") -> object:
    """`value` as orjson writes it: floats rounded (non-finite ones null), arrays flat,
    images in base64."""
    digits = RADIAN_DIGITS if key in _ANGLE_KEYS else METRE_DIGITS
    if isinstance(value, np.ndarray):
        if value.dtype.kind == "f":
            return np.round(value, digits).reshape(-1)
        return np.ascontiguousarray(value).reshape(-1)
    if isinstance(value, float):
        return round(value, digits) if math.isfinite(value) else None
    if isinstance(value, dict):
        return {k: _plain(v, k) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [v if isinstance(v, str | int) else _plain(v, key) for v in value]
    if isinstance(value, SensorImage):
        return {
            "name": value.name,
            "mime": value.mime,
            "data": base64.b64encode(value.data).decode("ascii"),
            "stamp": round(value.stamp, 3),
        }
    return value


def encode(message: Message) -> str:
    """JSON text of a map, a captured frame or the plots' history (server thread)."""
    plain: Mapping[str, object] = message
    if "objects" in message:
        plain = {**message, "objects": _objects(message["objects"])}
    # orjson writes numpy arrays itself (NaN as null), several times faster than json.
    return orjson.dumps(_plain(plain), option=orjson.OPT_SERIALIZE_NUMPY).decode()
