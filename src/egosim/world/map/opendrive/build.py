"""An OpenDRIVE document (its XML text) -> a LaneMap."""

from __future__ import annotations

from egosim.world.map.builtin_origin import assumed_georeference
from egosim.world.map.errors import MapGeometryError, MapRecordError
from egosim.world.map.georef import GeoReference
from egosim.world.map.lanes import Lane, LaneMap, Sidewalk
from egosim.world.map.opendrive.crosswalks import road_crosswalks
from egosim.world.map.opendrive.document import SOURCE, Document, read_document
from egosim.world.map.opendrive.road_frame import OpenDriveRoads
from egosim.world.map.opendrive.road_lanes import LaneKey, RoadLane, road_lanes, road_markings
from egosim.world.map.opendrive.signals import build_signals
from egosim.world.map.opendrive.topology import lane_links, neighbours
from egosim.world.map.opendrive.virtual_junctions import cut_at_joins


def build_opendrive_map(name: str, xml_text: str, notes: list[str]) -> LaneMap:
    """The LaneMap of an OpenDRIVE document.

    Raises MapRecordError naming the element of any malformed data (its source is
    "OpenDRIVE"; file loaders put the path there); appends to `notes` one line per thing
    it read but left out.
    """
    document = read_document(xml_text)
    notes.extend(document.notes)
    cut_at_joins(document)
    georef = read_georeference(document, notes)
    lanes: dict[LaneKey, RoadLane] = {}
    sidewalks: list[Sidewalk] = []
    for road in document.roads.values():
        road_drivable, road_sidewalks = road_lanes(road, notes)
        lanes.update((lane.key, lane) for lane in road_drivable)
        sidewalks.extend(road_sidewalks)
    successors, predecessors = lane_links(document, lanes)
    sides = neighbours(lanes)
    lights, intersections, stop_lines = build_signals(document, lanes, predecessors, notes)
    crosswalks = [
        crosswalk
        for road in document.roads.values()
        for crosswalk in road_crosswalks(road, intersections, notes)
    ]
    for tag, count in document.unread.items():
        notes.append(f"{count} <{tag}> elements not read")
    built = []
    for lane in lanes.values():
        stop = stop_lines.get(lane.id)
        try:
            built.append(
                Lane(
                    id=lane.id,
                    centerline=lane.centerline,
                    widths=lane.widths,
                    speed_limit=lane.speed_limit,
                    successors=tuple(successors.get(lane.id, ())),
                    predecessors=tuple(predecessors.get(lane.id, ())),
                    left_neighbor=sides[lane.id][0],
                    right_neighbor=sides[lane.id][1],
                    stop_line_s=None if stop is None else stop.station,
                    traffic_light_ids=() if stop is None else tuple(stop.light_ids),
                    is_junction=lane.in_junction,
                )
            )
        except MapGeometryError as error:
            raise MapRecordError(SOURCE, f"road id={lane.key.road!r}", str(error)) from None
    markings = [m for road in document.roads.values() for m in road_markings(road, notes)]
    try:
        lane_map = LaneMap(name, built, lights, intersections, crosswalks, sidewalks, georef)
    except MapGeometryError as error:
        raise MapRecordError(SOURCE, "lane graph", str(error)) from None
    lane_map = lane_map.with_markings(markings)
    return lane_map.with_roads(OpenDriveRoads(document.roads, lanes, lane_map))


def read_georeference(document: Document, notes: list[str]) -> GeoReference:
    """The header's geoReference with its <offset> as the local origin in that projection."""
    x, y, z, heading = document.offset
    if document.geo_reference is None:
        notes.append(
            "header has no geoReference: placed at the built-in maps' origin (UTM zone 52N, "
            "Seoul); its GPS latitudes and longitudes are invented"
        )
        return assumed_georeference()
    if heading != 0.0:
        notes.append(f"header offset hdg={heading} not applied: the map is read unrotated")
    try:
        return GeoReference.from_projection(document.geo_reference, (x, y, z))
    except ValueError as error:
        raise MapRecordError(SOURCE, "header geoReference", str(error)) from None
