"""Lane-to-lane links of an OpenDRIVE network: successors, predecessors and neighbours.

Links are gathered as pairs of touching lane ends, from lane links between sections of a
road, from lane links across road links (at the contact point of the other road, or for a
road of a virtual junction at the station it joins the other road: that road's sections
are cut there, see virtual_junctions), and from junction connections' laneLinks (into the
connecting road of a default or virtual junction, the linked road of a direct one). A pair
becomes a successor link when one lane leaves through its end and the other enters
through its end, whatever the lanes' directions.
"""

from __future__ import annotations

from collections import defaultdict

from egosim.world.map.opendrive.document import Connection, Document, Junction, LinkTarget, Road
from egosim.world.map.opendrive.road_lanes import LaneKey, RoadLane, lane_id, section_range
from egosim.world.map.opendrive.virtual_junctions import SAME_STATION_M, joined_station

# A lane end: (lane, True for the end at the section's larger s).
LaneEnd = tuple[LaneKey, bool]


def lane_links(
    document: Document, lanes: dict[LaneKey, RoadLane]
) -> tuple[dict[str, list[str]], dict[str, list[str]]]:
    """Successors and predecessors by lane id."""
    successors: dict[str, list[str]] = defaultdict(list)
    predecessors: dict[str, list[str]] = defaultdict(list)
    for a, b in sorted(_touching_ends(document, lanes)):
        for (out_key, out_far), (in_key, in_far) in ((a, b), (b, a)):
            leaves = lanes[out_key].forward == out_far
            enters = lanes[in_key].forward != in_far
            source, target = lane_id(out_key), lane_id(in_key)
            if leaves and enters and target not in successors[source]:
                successors[source].append(target)
                predecessors[target].append(source)
    return successors, predecessors


def neighbours(lanes: dict[LaneKey, RoadLane]) -> dict[str, tuple[str | None, str | None]]:
    """(left, right) lane-change neighbours: the adjacent lane of the same direction."""
    result = {}
    for key, lane in lanes.items():
        higher = _adjacent(lanes, key, key.lane + 1)
        lower = _adjacent(lanes, key, key.lane - 1)
        # Facing +s, +t (higher lane ids) is on the left.
        result[lane.id] = (higher, lower) if lane.forward else (lower, higher)
    return result


def _adjacent(lanes: dict[LaneKey, RoadLane], key: LaneKey, other: int) -> str | None:
    if other == 0 or (other > 0) != (key.lane > 0):
        return None
    neighbour = lanes.get(LaneKey(key.road, key.section, other))
    return None if neighbour is None else neighbour.id


def _touching_ends(
    document: Document, lanes: dict[LaneKey, RoadLane]
) -> set[tuple[LaneEnd, LaneEnd]]:
    pairs: set[tuple[LaneEnd, LaneEnd]] = set()

    def touch(a: LaneEnd, b: LaneEnd) -> None:
        if a[0] in lanes and b[0] in lanes:
            pairs.add((a, b) if a <= b else (b, a))

    for road in document.roads.values():
        last = len(road.sections) - 1
        for k, section in enumerate(road.sections):
            for record in section.lanes:
                here = LaneKey(road.id, k, record.id)
                if record.successor is not None:
                    if k < last:
                        touch((here, True), (LaneKey(road.id, k + 1, record.successor), False))
                    else:
                        for end in _road_ends(document, road.successor, record.successor):
                            touch((here, True), end)
                if record.predecessor is not None:
                    if k > 0:
                        touch((here, False), (LaneKey(road.id, k - 1, record.predecessor), True))
                    else:
                        for end in _road_ends(document, road.predecessor, record.predecessor):
                            touch((here, False), end)
    for junction in document.junctions.values():
        for connection in junction.connections:
            incoming = document.roads.get(connection.incoming_road)
            target = document.roads.get(connection.road)
            if incoming is None or target is None:
                continue
            for from_lane, to_lane in connection.lane_links:
                target_end = _connection_end(target, connection, to_lane)
                if target_end is None:
                    continue
                for incoming_end in _incoming_ends(incoming, junction, target, from_lane):
                    touch(incoming_end, target_end)
    return pairs


def _road_ends(document: Document, target: LinkTarget | None, lane: int) -> list[LaneEnd]:
    """The ends of lane `lane` of the road a road link points at: at its contact point,
    or at the station a road of a virtual junction joins it (junction links: none)."""
    if target is None or target.element_type != "road":
        return []
    road = document.roads.get(target.element_id)
    if road is None:
        return []
    if target.element_s is not None:
        return _ends_at(road, target.element_s, lane)
    return [_contact(road, target.contact_point or "start", lane)]


def _ends_at(road: Road, s: float, lane: int) -> list[LaneEnd]:
    """The ends of lane `lane` at station s: the end of the section up to s and the start
    of the section from s (the lane graph keeps those that lead the right way)."""
    ends = []
    for k in range(len(road.sections)):
        start, end = section_range(road, k)
        if abs(end - s) <= SAME_STATION_M:
            ends.append((LaneKey(road.id, k, lane), True))
        if abs(start - s) <= SAME_STATION_M:
            ends.append((LaneKey(road.id, k, lane), False))
    return ends


def _incoming_ends(incoming: Road, junction: Junction, target: Road, lane: int) -> list[LaneEnd]:
    """Where lane `lane` of a connection's incoming road meets the junction: the road end
    linked to the junction, or for a virtual junction the station the connecting road
    joins the incoming road at."""
    far = _faces_junction(incoming, junction.id)
    if far is not None:
        return [(LaneKey(incoming.id, len(incoming.sections) - 1 if far else 0, lane), far)]
    for link in (target.predecessor, target.successor):
        if (s := joined_station(link, incoming.id)) is not None:
            return _ends_at(incoming, s, lane)
    return []


def _connection_end(road: Road, connection: Connection, lane: int) -> LaneEnd | None:
    """The end of the connection's road where its lane `lane` is joined: its contact
    point, or (a virtual junction's connection giving none) the end linked to the incoming
    road."""
    if connection.contact_point is not None:
        return _contact(road, connection.contact_point, lane)
    for contact, link in (("start", road.predecessor), ("end", road.successor)):
        if joined_station(link, connection.incoming_road) is not None:
            return _contact(road, contact, lane)
    return None


def _contact(road: Road, contact_point: str, lane: int) -> LaneEnd:
    if contact_point == "end":
        return LaneKey(road.id, len(road.sections) - 1, lane), True
    return LaneKey(road.id, 0, lane), False


def _faces_junction(road: Road, junction_id: str) -> bool | None:
    """True if the road's end touches the junction, False for its start, None if neither."""
    for far, target in ((True, road.successor), (False, road.predecessor)):
        if (
            target is not None
            and target.element_type == "junction"
            and (target.element_id == junction_id)
        ):
            return far
    return None
