"""MGeo traffic lights -> signal heads: type, position, facing and the lanes they govern.

A light governs the stop line at the end of the links in its `link_id_list`. When a listed
link starts at a stop-line node (a connector past the line), the links arriving at that
node are governed instead: a stop line belongs to the lane that ends at it. Several heads
may govern one stop line (K-City hangs a round-green head and a left-arrow head over the
same lanes); each keeps every lane it lists.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from egosim.world.map.lanes import Lane
from egosim.world.map.light_type import LightType
from egosim.world.map.mgeo.light_types import light_type_of
from egosim.world.map.mgeo.links import LinkEnds
from egosim.world.map.mgeo.nodes import Node
from egosim.world.map.mgeo.records import Record, unique_by_idx

VEHICLE_LIGHT_TYPES = frozenset({"car", "vehicle"})


@dataclass(frozen=True)
class LightHead:
    """A vehicle signal head before it is placed in an intersection."""

    idx: str
    position: tuple[float, float, float]
    heading: float
    light_type: LightType
    lane_ids: tuple[str, ...]


def read_light_heads(
    items: list[Record],
    lanes: dict[str, Lane],
    ends: dict[str, LinkEnds],
    nodes: dict[str, Node] | None,
    notes: list[str],
) -> list[LightHead]:
    """The vehicle heads in file order."""
    heads = []
    for idx, record in unique_by_idx(items).items():
        kind = (record.text("type") or "car").lower()
        if kind not in VEHICLE_LIGHT_TYPES:
            notes.append(f"traffic_light_set.json: {idx}: {kind} light ignored")
            continue
        light_type = light_type_of(record.data.get("sub_type"))
        if light_type is None:
            notes.append(
                f"traffic_light_set.json: {idx}: sub_type {record.data.get('sub_type')!r} "
                "read as R/Y/G"
            )
            light_type = LightType.RYG
        lane_ids = _stop_line_lanes(record, lanes, ends, nodes, notes)
        x, y, z = (float(v) for v in record.point("point"))
        heads.append(LightHead(idx, (x, y, z), _facing(lanes, lane_ids), light_type, lane_ids))
    return heads


def _stop_line_lanes(
    record: Record,
    lanes: dict[str, Lane],
    ends: dict[str, LinkEnds],
    nodes: dict[str, Node] | None,
    notes: list[str],
) -> tuple[str, ...]:
    chosen: dict[str, None] = {}
    for link_id in record.ids("link_id_list"):
        if link_id not in lanes:
            notes.append(f"traffic_light_set.json: {record.idx}: link {link_id} is not a lane")
            continue
        link_ends = ends[link_id]
        past_the_line = (
            nodes is not None
            and nodes[link_ends.from_node].on_stop_line
            and not nodes[link_ends.to_node].on_stop_line
        )
        targets = lanes[link_id].predecessors if past_the_line else (link_id,)
        chosen.update(dict.fromkeys(targets))
    return tuple(chosen)


def _facing(lanes: dict[str, Lane], lane_ids: tuple[str, ...]) -> float:
    """A head faces the cars it governs: against the travel direction at the stop line."""
    if not lane_ids:
        return 0.0
    line = lanes[lane_ids[0]].centerline
    dx, dy = line[-1, :2] - line[-2, :2]
    return math.remainder(math.atan2(dy, dx) + math.pi, math.tau)
