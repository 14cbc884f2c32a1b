"""The parts of an OpenDRIVE document the loader uses, read from its XML element tree."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from collections.abc import Sequence
from dataclasses import dataclass, field

from egosim.world.map.errors import MapRecordError
from egosim.world.map.opendrive.geometry import (
    Arc,
    Geometry,
    Line,
    ParamPoly3,
    Pose2,
    Spiral,
)
from egosim.world.map.opendrive.polynomials import Cubic

SOURCE = "OpenDRIVE"
"""Source named by errors; the file loader replaces it with the file's path."""

_SPEED_UNITS = {"m/s": 1.0, "km/h": 1.0 / 3.6, "mph": 0.44704}


@dataclass(frozen=True)
class LinkTarget:
    element_type: str
    """"road" or "junction"."""
    element_id: str
    contact_point: str | None
    """"start" or "end" of the target road."""
    element_s: float | None = None
    """Station on the target road a road of a virtual junction joins it at (1.7+), m."""


@dataclass(frozen=True)
class RoadMarkRecord:
    """<roadMark>: the paint on a lane's outer border from `s_offset` (m into the section)."""

    s_offset: float
    type: str
    color: str
    width: float | None


@dataclass(frozen=True)
class LaneRecord:
    id: int
    type: str
    widths: tuple[Cubic, ...]
    predecessor: int | None
    successor: int | None
    speed: float | None
    """m/s, from the lane's first <speed>."""
    has_border: bool
    road_marks: tuple[RoadMarkRecord, ...] = ()


@dataclass(frozen=True)
class LaneSection:
    s: float
    lanes: tuple[LaneRecord, ...]
    """Left and right lanes (not the centre lane), in file order."""
    center_marks: tuple[RoadMarkRecord, ...] = ()
    """The centre lane's road marks (on the reference line shifted by laneOffset)."""


@dataclass(frozen=True)
class SignalRecord:
    id: str
    s: float
    t: float
    z_offset: float
    orientation: str
    """"+" (valid for traffic along +s), "-" or "none"."""
    dynamic: bool
    type: str
    subtype: str
    valid_lanes: tuple[tuple[int, int], ...]
    """(fromLane, toLane) ranges of <validity>; empty: every lane of its direction."""
    is_reference: bool
    """A <signalReference> to a signal placed on another road."""


@dataclass(frozen=True)
class CrosswalkRecord:
    """An <object type="crosswalk">: its origin at (s, t) on the road and its outline."""

    id: str
    s: float
    t: float
    hdg: float
    """Heading of the object's u axis relative to the reference line, rad."""
    length: float
    """Along u, m (0: not given)."""
    width: float
    """Along v, m (0: not given)."""
    road_corners: tuple[tuple[float, float], ...]
    """(s, t) of the outline's <cornerRoad> points."""
    local_corners: tuple[tuple[float, float], ...]
    """(u, v) of the outline's <cornerLocal> points, in the object's frame."""


@dataclass(frozen=True)
class Road:
    id: str
    length: float
    junction: str
    rule: str
    """"RHT" or "LHT"."""
    predecessor: LinkTarget | None
    successor: LinkTarget | None
    geometries: tuple[tuple[float, Pose2, Geometry], ...]
    """(s, start pose, geometry) in plan-view order."""
    lane_offsets: tuple[Cubic, ...]
    elevation: tuple[Cubic, ...]
    sections: tuple[LaneSection, ...]
    signals: tuple[SignalRecord, ...]
    type_speeds: tuple[tuple[float, float], ...]
    """(s, m/s) of <type><speed>."""
    crosswalks: tuple[CrosswalkRecord, ...] = ()

    @property
    def in_junction(self) -> bool:
        return self.junction not in ("", "-1")


JUNCTION_TYPES = ("default", "direct", "virtual", "crossing")
"""Junction types of OpenDRIVE 1.4 (default) to 1.8 (crossing)."""


@dataclass(frozen=True)
class Connection:
    id: str
    incoming_road: str
    """"" where a virtual junction's connection names none."""
    road: str
    """The road the connection leads into: the connecting road (default and virtual
    junctions) or the linked road (direct junctions)."""
    contact_point: str | None
    """"start" or "end" of `road`; None where a virtual junction's connection gives none."""
    lane_links: tuple[tuple[int, int], ...]
    predecessor: LinkTarget | None = None
    successor: LinkTarget | None = None
    """A 1.7 virtual connection's own links of its connecting road (1.8 puts them on the
    road)."""


@dataclass(frozen=True)
class Junction:
    id: str
    connections: tuple[Connection, ...]
    controllers: tuple[str, ...]
    """Controller ids in the order of their `sequence` attribute."""
    type: str = "default"
    """One of JUNCTION_TYPES."""

    @property
    def connecting_roads(self) -> set[str]:
        """The roads through the junction (a direct junction's linked roads are ordinary
        roads around it, not through it)."""
        return set() if self.type == "direct" else {c.road for c in self.connections}


@dataclass(frozen=True)
class Controller:
    id: str
    signal_ids: tuple[str, ...]


@dataclass
class Document:
    geo_reference: str | None
    offset: tuple[float, float, float, float]
    """x, y, z, hdg of the header's <offset>."""
    roads: dict[str, Road] = field(default_factory=dict)
    junctions: dict[str, Junction] = field(default_factory=dict)
    controllers: dict[str, Controller] = field(default_factory=dict)
    unread: dict[str, int] = field(default_factory=dict)
    """Element tags the loader does not read -> how many."""
    notes: list[str] = field(default_factory=list)
    """One line per record read but left out."""


class _Element:
    """An XML element with attribute readers that fail naming the record."""

    def __init__(self, element: ET.Element, label: str) -> None:
        self.element = element
        self.label = label

    def fail(self, reason: str) -> MapRecordError:
        return MapRecordError(SOURCE, self.label, reason)

    def text(self, name: str, default: str | None = None) -> str:
        value = self.element.get(name, default)
        if value is None:
            raise self.fail(f"has no attribute {name!r}")
        return value.strip()

    def number(self, name: str, default: float | None = None) -> float:
        raw = self.element.get(name)
        if raw is None:
            if default is None:
                raise self.fail(f"has no attribute {name!r}")
            return default
        try:
            value = float(raw)
        except ValueError:
            raise self.fail(f"attribute {name}={raw!r} is not a number") from None
        if not math.isfinite(value):
            raise self.fail(f"attribute {name}={raw!r} is not finite")
        return value

    def integer(self, name: str) -> int:
        raw = self.text(name)
        try:
            value = float(raw)
            if not value.is_integer():
                raise ValueError(raw)
            return int(value)
        except ValueError:
            raise self.fail(f"attribute {name}={raw!r} is not an integer") from None

    def child(self, tag: str, label: str) -> _Element | None:
        found = self.element.find(tag)
        return None if found is None else _Element(found, f"{self.label} {label}")

    def children(self, path: str, label: str) -> list[_Element]:
        return [
            _Element(e, f"{self.label} {label} #{k}")
            for k, e in enumerate(self.element.findall(path))
        ]

    def cubic(self, start_name: str = "s", start: float = 0.0) -> Cubic:
        return Cubic(
            start + self.number(start_name),
            self.number("a"),
            self.number("b"),
            self.number("c"),
            self.number("d"),
        )


def read_document(xml_text: str) -> Document:
    try:
        root = ET.fromstring(xml_text)
    except ET.ParseError as error:
        raise MapRecordError(SOURCE, "XML", str(error)) from None
    if root.tag != "OpenDRIVE":
        raise MapRecordError(SOURCE, "XML", f"root element is <{root.tag}>, not <OpenDRIVE>")
    top = _Element(root, "OpenDRIVE")
    header = top.child("header", "header")
    document = Document(geo_reference=None, offset=(0.0, 0.0, 0.0, 0.0))
    if header is not None:
        geo = header.element.find("geoReference")
        if geo is not None and (geo.text or "").strip():
            document.geo_reference = (geo.text or "").strip()
        offset = header.child("offset", "offset")
        if offset is not None:
            x, y, z, hdg = (offset.number(n, 0.0) for n in ("x", "y", "z", "hdg"))
            document.offset = (x, y, z, hdg)
    for road in top.children("road", "road"):
        parsed = _road(road)
        if parsed.id in document.roads:
            raise road.fail(f"repeats road id {parsed.id}")
        document.roads[parsed.id] = parsed
    for junction in top.children("junction", "junction"):
        parsed_junction = _junction(junction, document.notes)
        document.junctions[parsed_junction.id] = parsed_junction
    for controller in top.children("controller", "controller"):
        controller.label = f"controller id={controller.text('id')!r}"
        signal_ids = tuple(c.text("signalId") for c in controller.children("control", "control"))
        document.controllers[controller.text("id")] = Controller(controller.text("id"), signal_ids)
    for element in root:
        if element.tag not in ("header", "road", "junction", "controller"):
            document.unread[element.tag] = document.unread.get(element.tag, 0) + 1
    return document


def _road(road: _Element) -> Road:
    road.label = f"road id={road.text('id')!r}"
    link = road.child("link", "link")
    predecessor = successor = None
    if link is not None:
        predecessor = _link_target(link.child("predecessor", "predecessor"))
        successor = _link_target(link.child("successor", "successor"))
    geometries = tuple(_geometry(g) for g in road.children("planView/geometry", "geometry"))
    if not geometries:
        raise road.fail("has no planView geometry")
    lanes = road.child("lanes", "lanes")
    if lanes is None:
        raise road.fail("has no lanes")
    sections = tuple(_section(s) for s in lanes.children("laneSection", "laneSection"))
    if not sections:
        raise road.fail("has no laneSection")
    signals = tuple(_signal(s, False) for s in road.children("signals/signal", "signal"))
    references = tuple(
        _signal(s, True) for s in road.children("signals/signalReference", "signalReference")
    )
    return Road(
        id=road.text("id"),
        length=road.number("length"),
        junction=road.text("junction", "-1"),
        rule=road.text("rule", "RHT").upper(),
        predecessor=predecessor,
        successor=successor,
        geometries=geometries,
        lane_offsets=tuple(
            sorted((o.cubic() for o in lanes.children("laneOffset", "laneOffset")), key=_start)
        ),
        elevation=tuple(
            sorted(
                (e.cubic() for e in road.children("elevationProfile/elevation", "elevation")),
                key=_start,
            )
        ),
        sections=tuple(sorted(sections, key=lambda section: section.s)),
        signals=signals + references,
        type_speeds=tuple(
            (t.number("s"), _speed(speed))
            for t in road.children("type", "type")
            if (speed := t.child("speed", "speed")) is not None
        ),
        crosswalks=tuple(
            _crosswalk(o)
            for o in road.children("objects/object", "object")
            if o.element.get("type", "").strip().lower() == "crosswalk"
        ),
    )


def _crosswalk(element: _Element) -> CrosswalkRecord:
    element.label = f"{element.label} id={element.text('id')!r}"
    outline = "outline", "outlines/outline"
    road_corners = [c for o in outline for c in element.children(f"{o}/cornerRoad", "cornerRoad")]
    local = [c for o in outline for c in element.children(f"{o}/cornerLocal", "cornerLocal")]
    return CrosswalkRecord(
        id=element.text("id"),
        s=element.number("s"),
        t=element.number("t", 0.0),
        hdg=element.number("hdg", 0.0),
        length=element.number("length", 0.0),
        width=element.number("width", 0.0),
        road_corners=tuple((c.number("s"), c.number("t")) for c in road_corners),
        local_corners=tuple((c.number("u"), c.number("v")) for c in local),
    )


def _start(cubic: Cubic) -> float:
    return cubic.start


def _link_target(element: _Element | None) -> LinkTarget | None:
    if element is None:
        return None
    contact = element.element.get("contactPoint")
    element_s = element.number("elementS") if element.element.get("elementS") else None
    return LinkTarget(
        element.text("elementType", "road"), element.text("elementId"), contact, element_s
    )


def _geometry(element: _Element) -> tuple[float, Pose2, Geometry]:
    s, length = element.number("s"), element.number("length")
    if length <= 0.0:
        raise element.fail(f"length must be positive, got {length}")
    start = Pose2(element.number("x"), element.number("y"), element.number("hdg"))
    shape = next(iter(element.element), None)
    if shape is None:
        raise element.fail("has no line, arc, spiral, poly3 or paramPoly3")
    shape_element = _Element(shape, f"{element.label} {shape.tag}")
    geometry: Geometry
    if shape.tag == "line":
        geometry = Line(length)
    elif shape.tag == "arc":
        geometry = Arc(length, shape_element.number("curvature"))
    elif shape.tag == "spiral":
        geometry = Spiral(
            length, shape_element.number("curvStart"), shape_element.number("curvEnd")
        )
    elif shape.tag == "poly3":
        geometry = ParamPoly3(
            length, (0.0, 1.0, 0.0, 0.0), _coefficients(shape_element, "abcd"), length, u_is_p=True
        )
    elif shape.tag == "paramPoly3":
        u = _coefficients(shape_element, ("aU", "bU", "cU", "dU"))
        v = _coefficients(shape_element, ("aV", "bV", "cV", "dV"))
        normalized = shape_element.text("pRange", "normalized") == "normalized"
        geometry = ParamPoly3(length, u, v, 1.0 if normalized else length)
    else:
        raise shape_element.fail("is not a line, arc, spiral, poly3 or paramPoly3")
    return s, start, geometry


def _coefficients(element: _Element, names: Sequence[str]) -> tuple[float, float, float, float]:
    a, b, c, d = (element.number(name) for name in names)
    return a, b, c, d


def _section(section: _Element) -> LaneSection:
    s = section.number("s")
    section.label = f"{section.label} (s={s:g})"
    records = []
    for side in ("left", "right"):
        for lane in section.children(f"{side}/lane", f"{side} lane"):
            lane.label = f"{section.label} lane id={lane.text('id')!r}"
            records.append(_lane(lane))
    centre = section.child("center/lane", "center lane")
    return LaneSection(s, tuple(records), _road_marks(centre) if centre is not None else ())


def _road_marks(lane: _Element) -> tuple[RoadMarkRecord, ...]:
    marks = [
        RoadMarkRecord(
            s_offset=mark.number("sOffset", 0.0),
            type=mark.text("type", "none"),
            color=mark.text("color", "standard"),
            width=mark.number("width") if mark.element.get("width") is not None else None,
        )
        for mark in lane.children("roadMark", "roadMark")
    ]
    return tuple(sorted(marks, key=lambda m: m.s_offset))


def _lane(lane: _Element) -> LaneRecord:
    link = lane.child("link", "link")
    predecessor = successor = None
    if link is not None:
        if (p := link.child("predecessor", "predecessor")) is not None:
            predecessor = p.integer("id")
        if (n := link.child("successor", "successor")) is not None:
            successor = n.integer("id")
    speeds = lane.children("speed", "speed")
    return LaneRecord(
        id=lane.integer("id"),
        type=lane.text("type", "none"),
        widths=tuple(
            sorted((w.cubic("sOffset") for w in lane.children("width", "width")), key=_start)
        ),
        predecessor=predecessor,
        successor=successor,
        speed=_speed(speeds[0]) if speeds else None,
        has_border=lane.element.find("border") is not None,
        road_marks=_road_marks(lane),
    )


def _speed(element: _Element) -> float:
    unit = element.text("unit", "m/s")
    if unit not in _SPEED_UNITS:
        raise element.fail(f"unknown speed unit {unit!r}")
    return element.number("max") * _SPEED_UNITS[unit]


def _signal(signal: _Element, is_reference: bool) -> SignalRecord:
    signal.label = f"{signal.label} id={signal.text('id')!r}"
    valid = tuple(
        (v.integer("fromLane"), v.integer("toLane"))
        for v in signal.children("validity", "validity")
    )
    return SignalRecord(
        id=signal.text("id"),
        s=signal.number("s"),
        t=signal.number("t", 0.0),
        z_offset=signal.number("zOffset", 0.0),
        orientation=signal.text("orientation", "none"),
        dynamic=signal.text("dynamic", "no") == "yes",
        type=signal.text("type", ""),
        subtype=signal.text("subtype", ""),
        valid_lanes=valid,
        is_reference=is_reference,
    )


def _junction(junction: _Element, notes: list[str]) -> Junction:
    junction.label = f"junction id={junction.text('id')!r}"
    kind = junction.text("type", "default")
    if kind not in JUNCTION_TYPES:
        notes.append(f"{junction.label}: type {kind!r} is unknown, read as a default junction")
        kind = "default"
    connections = []
    for connection in junction.children("connection", "connection"):
        connection.label = f"{junction.label} connection id={connection.text('id', '?')!r}"
        parsed = _connection(connection, kind, notes)
        if parsed is not None:
            connections.append(parsed)
    controls = junction.children("controller", "controller")
    ordered = sorted(controls, key=lambda c: c.number("sequence", 0.0))
    return Junction(
        junction.text("id"), tuple(connections), tuple(c.text("id") for c in ordered), kind
    )


def _contact_point(connection: _Element, kind: str) -> str | None:
    """A connection's contact point: "start" by default, none in a virtual junction."""
    contact = connection.element.get("contactPoint")
    if contact is None:
        return None if kind == "virtual" else "start"
    return contact.strip()


def _connection(connection: _Element, kind: str, notes: list[str]) -> Connection | None:
    """A junction's connection; None (noted) for one that names no road to lead into, or
    no incoming road outside a virtual junction."""
    road = connection.element.get("connectingRoad") or connection.element.get("linkedRoad")
    incoming = connection.element.get("incomingRoad", "")
    if not road or (not incoming and kind != "virtual"):
        missing = "connectingRoad nor linkedRoad" if not road else "incomingRoad"
        notes.append(f"{connection.label}: names no {missing}, left out")
        return None
    return Connection(
        id=connection.text("id", ""),
        incoming_road=incoming.strip(),
        road=road.strip(),
        contact_point=_contact_point(connection, kind),
        lane_links=tuple(
            (link.integer("from"), link.integer("to"))
            for link in connection.children("laneLink", "laneLink")
        ),
        predecessor=_link_target(connection.child("predecessor", "predecessor")),
        successor=_link_target(connection.child("successor", "successor")),
    )
