"""An MGeo map (its JSON files, already parsed) -> a LaneMap."""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping

from egosim.world.map.errors import MapGeometryError, MapRecordError
from egosim.world.map.georef import GeoReference
from egosim.world.map.lanes import Lane, LaneMap
from egosim.world.map.mgeo.crosswalks import SINGLECROSSWALK_SET, read_crosswalks
from egosim.world.map.mgeo.intersections import build_intersections
from egosim.world.map.mgeo.lights import read_light_heads
from egosim.world.map.mgeo.links import LinkEnds, read_lanes
from egosim.world.map.mgeo.markings import read_markings
from egosim.world.map.mgeo.nodes import Node, read_nodes
from egosim.world.map.mgeo.records import Record, records, unique_by_idx

GLOBAL_INFO = "global_info.json"
NODE_SET = "node_set.json"
LINK_SET = "link_set.json"
LANE_BOUNDARY_SET = "lane_boundary_set.json"
TRAFFIC_LIGHT_SET = "traffic_light_set.json"
SYNCED_TRAFFIC_LIGHT_SET = "synced_traffic_light_set.json"
INTERSECTION_CONTROLLER_SET = "intersection_controller_set.json"
MGEO_FILES = (
    GLOBAL_INFO,
    NODE_SET,
    LINK_SET,
    LANE_BOUNDARY_SET,
    TRAFFIC_LIGHT_SET,
    SYNCED_TRAFFIC_LIGHT_SET,
    INTERSECTION_CONTROLLER_SET,
    SINGLECROSSWALK_SET,
)
"""The files the loader reads; a folder's other files are reported as ignored."""
REQUIRED_FILES = (GLOBAL_INFO, LINK_SET)


def build_mgeo_map(name: str, files: Mapping[str, object], notes: list[str]) -> LaneMap:
    """The LaneMap of an MGeo map given as {file name: parsed JSON} (see MGEO_FILES).

    Raises MapRecordError naming the file and record of any malformed data; appends to
    `notes` one line per thing it read but left out.
    """
    for required in REQUIRED_FILES:
        if required not in files:
            raise MapRecordError(required, "file", "is missing")
    georef = read_georeference(files[GLOBAL_INFO])
    nodes = read_nodes(_records(files, NODE_SET)) if NODE_SET in files else None
    boundaries = {
        idx: record.points("points")
        for idx, record in unique_by_idx(_records(files, LANE_BOUNDARY_SET)).items()
    }
    lanes, ends = read_lanes(_records(files, LINK_SET), nodes, boundaries, notes)
    heads = read_light_heads(_records(files, TRAFFIC_LIGHT_SET), lanes, ends, nodes, notes)
    lights, intersections = build_intersections(
        heads,
        _records(files, SYNCED_TRAFFIC_LIGHT_SET),
        _records(files, INTERSECTION_CONTROLLER_SET),
        notes,
    )
    lights_of_lane: dict[str, list[str]] = {}
    for light in lights:
        for lane_id in light.lane_ids:
            lights_of_lane.setdefault(lane_id, []).append(light.id)
    lanes = _with_stop_lines(lanes, ends, nodes, lights_of_lane)
    try:
        lane_map = LaneMap(name, lanes.values(), lights, intersections, (), (), georef)
    except MapGeometryError as error:
        raise MapRecordError(LINK_SET, "lane graph", str(error)) from None
    crossings = _records(files, SINGLECROSSWALK_SET)
    markings = read_markings(_records(files, LANE_BOUNDARY_SET), notes)
    return lane_map.with_crosswalks(read_crosswalks(crossings, lane_map, notes)).with_markings(
        markings
    )


def read_georeference(data: object) -> GeoReference:
    """global_info.json: `global_coordinate_system` and `local_origin_in_global`."""
    info = Record(GLOBAL_INFO, 0, data)
    info.label = "global info"
    system = info.text("global_coordinate_system")
    if system is None:
        raise info.fail("has no global_coordinate_system")
    x, y, z = info.point("local_origin_in_global")
    try:
        return GeoReference.from_projection(system, (x, y, z))
    except ValueError as error:
        raise info.fail(f"global_coordinate_system: {error}") from None


def _records(files: Mapping[str, object], name: str) -> list[Record]:
    return records(name, files[name]) if name in files else []


def _with_stop_lines(
    lanes: dict[str, Lane],
    ends: dict[str, LinkEnds],
    nodes: dict[str, Node] | None,
    lights_of_lane: dict[str, list[str]],
) -> dict[str, Lane]:
    """Stop lines at the end of lanes reaching a stop-line node or governed by a light."""
    result = {}
    for idx, lane in lanes.items():
        on_line = nodes is not None and nodes[ends[idx].to_node].on_stop_line
        heads = tuple(lights_of_lane.get(idx, ()))
        result[idx] = (
            dataclasses.replace(lane, stop_line_s=lane.length, traffic_light_ids=heads)
            if on_line or heads
            else lane
        )
    return result
