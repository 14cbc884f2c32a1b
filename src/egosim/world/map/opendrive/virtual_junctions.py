"""Virtual junctions (OpenDRIVE 1.7+): roads that leave or join a main road part way along
it, at a station (`elementS` of their links), without cutting the main road.

A lane graph joins lanes at their ends only, so every road is cut into one more lane
section at each station where a road of a virtual junction joins it: its lanes end and
start there, and the joining road links to those lane ends like to any other. A 1.7
virtual connection's own <predecessor>/<successor> count as its connecting road's links
where the road gives none (1.8 puts them on the road).
"""

from __future__ import annotations

import dataclasses

from egosim.world.map.opendrive.document import (
    Document,
    LaneSection,
    LinkTarget,
    Road,
    RoadMarkRecord,
)
from egosim.world.map.opendrive.polynomials import Cubic

SAME_STATION_M = 1e-6
"""A join this close to a section boundary or road end uses it."""


def cut_at_joins(document: Document) -> None:
    """Give connecting roads their virtual connections' links and cut every joined road's
    lane sections at the stations roads join it."""
    for junction in document.junctions.values():
        if junction.type != "virtual":
            continue
        for connection in junction.connections:
            road = document.roads.get(connection.road)
            if road is not None:
                document.roads[road.id] = dataclasses.replace(
                    road,
                    predecessor=road.predecessor or connection.predecessor,
                    successor=road.successor or connection.successor,
                )
    stations: dict[str, set[float]] = {}
    for road in document.roads.values():
        for target in (road.predecessor, road.successor):
            if target is not None and target.element_type == "road" and target.element_s:
                stations.setdefault(target.element_id, set()).add(target.element_s)
    for road_id, cuts in stations.items():
        road = document.roads.get(road_id)
        if road is not None:
            document.roads[road_id] = _cut(road, sorted(cuts))


def joined_station(target: LinkTarget | None, road_id: str) -> float | None:
    """The station of road `road_id` a link joins it at mid-road, else None."""
    if target is None or target.element_type != "road" or target.element_id != road_id:
        return None
    return target.element_s


def _cut(road: Road, stations: list[float]) -> Road:
    sections = list(road.sections)
    for s in stations:
        if not SAME_STATION_M < s < road.length - SAME_STATION_M:
            continue
        k = max(i for i, section in enumerate(sections) if section.s <= s + SAME_STATION_M)
        if abs(sections[k].s - s) <= SAME_STATION_M:
            continue
        sections[k : k + 1] = [_until(sections[k]), _from(sections[k], s)]
    return dataclasses.replace(road, sections=tuple(sections))


def _until(section: LaneSection) -> LaneSection:
    """The part of `section` before a cut: each lane continues as itself after it."""
    lanes = tuple(dataclasses.replace(lane, successor=lane.id) for lane in section.lanes)
    return dataclasses.replace(section, lanes=lanes)


def _from(section: LaneSection, s: float) -> LaneSection:
    """The part of `section` from station s: the same lanes, their polynomials and marks
    measured from s; each lane continues as itself across the cut."""
    shift = s - section.s
    lanes = tuple(
        dataclasses.replace(
            lane,
            widths=tuple(_shifted(w, shift) for w in lane.widths),
            road_marks=_marks_from(lane.road_marks, shift),
            predecessor=lane.id,
        )
        for lane in section.lanes
    )
    return LaneSection(s, lanes, _marks_from(section.center_marks, shift))


def _shifted(cubic: Cubic, shift: float) -> Cubic:
    return dataclasses.replace(cubic, start=cubic.start - shift)


def _marks_from(marks: tuple[RoadMarkRecord, ...], shift: float) -> tuple[RoadMarkRecord, ...]:
    """The marks in force from `shift` on, offsets measured from there (the one in force
    at the cut starts at 0)."""
    later = [m for m in marks if m.s_offset > shift]
    current = [m for m in marks if m.s_offset <= shift][-1:]
    return tuple(
        dataclasses.replace(m, s_offset=max(m.s_offset - shift, 0.0)) for m in current + later
    )
