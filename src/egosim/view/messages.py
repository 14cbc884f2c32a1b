"""What passes between the server and the page: the map, frames, the plots' history and
the replies to the page's requests (the requests themselves are free-form JSON, read
field by field in controls.py).

A frame is captured on the loop thread with numpy arrays and the world's object tables
in it; `snapshot.encode` turns those into JSON on the server thread. Lengths are in m,
times in s, angles in rad, speeds in m/s.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Literal, TypeAlias, TypedDict, final

import numpy as np
import numpy.typing as npt

from ..json_value import JsonValue
from ..world.arrays import FloatArray
from ..world.map.light_type import LightType
from ..world.traffic import ObjectTable

Point: TypeAlias = list[float]
"""(x, y), rounded to the centimetre."""
Polyline: TypeAlias = list[Point]


@dataclass(frozen=True)
class SensorImage:
    """The latest image of one image sensor (a camera), ready for an <img> tag."""

    name: str
    mime: str
    """e.g. image/jpeg."""
    data: bytes
    stamp: float
    """Simulation time it was taken, s."""


ImageSource = Callable[[], SensorImage | None]
"""Called on the loop thread when a frame is taken; its latest image or None."""


# -- the map (once per page) -------------------------------------------------------------


class MapLane(TypedDict):
    id: str
    junction: bool
    outline: Polyline
    """The road surface: the left edge, then the right edge backwards."""


class MapMarking(TypedDict):
    points: Polyline
    style: Literal["dashed", "solid"]
    color: str
    double: bool


class MapJunction(TypedDict):
    id: int
    centre: Point


class MapCrosswalk(TypedDict):
    id: str
    start: Point
    end: Point
    width: float


class MapLight(TypedDict):
    id: str
    position: Point
    heading: float
    type: LightType


class AspectBits(TypedDict):
    """The lamp bits of an aspect, so the page decodes aspects with the world's codes."""

    red: int
    yellow: int
    green: int
    left: int


@final
class MapMessage(TypedDict):
    type: Literal["map"]
    name: str
    bounds: list[float]
    """(x min, y min, x max, y max)."""
    lanes: list[MapLane]
    markings: list[MapMarking]
    stop_lines: list[Polyline]
    junctions: list[MapJunction]
    crosswalks: list[MapCrosswalk]
    sidewalks: list[Polyline]
    lights: list[MapLight]
    aspect_bits: AspectBits
    aspect_off: int
    object_kinds: dict[str, int]
    """ObjectType codes by lower-case name."""


# -- frames ------------------------------------------------------------------------------


class EgoEntry(TypedDict):
    """One ego in a frame (the page's panel, plots and drawing read these)."""

    id: int
    model: str
    x: float
    y: float
    yaw: float
    length: float
    width: float
    centre_offset: float
    """Footprint centre ahead of the reference point (rear axle)."""
    speed: float
    forward_speed: float
    acceleration: float
    gear: str
    ctrl_mode: int
    steer: float
    accel_pedal: float
    brake_pedal: float
    lane_offset: float
    lane_id: str


class Collision(TypedDict):
    """When, and where the struck object (or the first vehicle of an NPC pair) stood."""

    t: float
    x: float
    y: float


class ReplayState(TypedDict):
    mode: str
    status: str
    position: float
    """s from the bag's start."""
    duration: float
    speed: int


@final
class CapturedFrame(TypedDict):
    """The world at one moment as the loop thread copies it out: numbers, array copies
    and the object tables (the world replaces, never edits, their arrays)."""

    type: Literal["frame"]
    sim_time: float
    paused: bool
    clock_mode: str
    real_time_factor: float | None
    sync_frame: int | None
    controls: bool
    followed: int
    egos: list[EgoEntry]
    objects: list[ObjectTable]
    light_aspects: npt.NDArray[np.int64]
    """In the order of the map's lights."""
    collisions: list[Collision]
    replay: ReplayState | None
    lidar: FloatArray | None
    """(N, 2) points in the map frame."""
    images: list[SensorImage]


class ObjectColumns(TypedDict):
    """NPCs, pedestrians and obstacles of an encoded frame, one array per field."""

    id: npt.NDArray[np.int64]
    kind: npt.NDArray[np.int64]
    x: FloatArray
    y: FloatArray
    yaw: FloatArray
    length: FloatArray
    width: FloatArray
    speed: FloatArray


# -- the plots' history (once per page) --------------------------------------------------

HistorySeries: TypeAlias = dict[str, int | FloatArray]
"""One ego's samples: its "id", then "t" and each plotted field as a column."""


@final
class HistoryMessage(TypedDict):
    type: Literal["history"]
    span_s: float
    spacing_s: float
    egos: list[HistorySeries]


Message: TypeAlias = MapMessage | CapturedFrame | HistoryMessage
"""What `snapshot.encode` turns into JSON (each has exactly its keys: @final, so a key
tells them apart)."""


# -- the hello (first on every socket) ---------------------------------------------------


class _HelloClock(TypedDict):
    type: Literal["hello"]
    clock_mode: str


class Hello(_HelloClock, total=False):
    """What the page learns first (the server adds "readonly")."""

    egosim_node: str


# -- replies to requests -----------------------------------------------------------------


class ReplyFields(TypedDict, total=False):
    """What a request's handler answers beside "ok"."""

    scenarios: list[str]
    loaded: str


class _ReplyOk(TypedDict):
    ok: bool


class Reply(_ReplyOk, ReplyFields, total=False):
    """The answer to one request: "ok", the request's "op" when it had one, an "error"
    text for the page when not ok."""

    op: JsonValue
    error: str
