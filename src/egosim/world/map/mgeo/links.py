"""MGeo links -> lanes: geometry, widths, speed limits, successors and lane-change neighbours.

A link is one directed lane between two nodes. A link with a non-empty `lane_ch_link_path`
is a lane-change manoeuvre drawn across two lanes, not a lane: it is left out (and counted
in the notes); the manoeuvre itself is what `left_neighbor` / `right_neighbor` express.
"""

from __future__ import annotations

from collections import defaultdict
from dataclasses import dataclass

import numpy as np

from egosim.world.arrays import FloatArray
from egosim.world.map.errors import MapGeometryError
from egosim.world.map.lanes import Lane
from egosim.world.map.mgeo.nodes import Node
from egosim.world.map.mgeo.records import Record, unique_by_idx
from egosim.world.map.mgeo.widths import link_widths
from egosim.world.map.polyline import stations

DEFAULT_SPEED_LIMIT_KPH = 50.0
# Consecutive points closer than this are one point (MGeo tools often repeat a vertex).
_SAME_POINT_M = 1e-6


@dataclass(frozen=True)
class LinkEnds:
    from_node: str
    to_node: str


def is_lane_change_link(link: Record) -> bool:
    return bool(link.ids("lane_ch_link_path"))


def read_lanes(
    items: list[Record],
    nodes: dict[str, Node] | None,
    boundaries: dict[str, FloatArray],
    notes: list[str],
) -> tuple[dict[str, Lane], dict[str, LinkEnds]]:
    """Lanes by link idx and the nodes each lane runs between."""
    links = {idx: r for idx, r in unique_by_idx(items).items() if not is_lane_change_link(r)}
    skipped = len(items) - len(links)
    if skipped:
        notes.append(f"link_set.json: {skipped} lane-change links are manoeuvres, not lanes")
    ends = {idx: _ends(link, nodes) for idx, link in links.items()}
    leaving: dict[str, list[str]] = defaultdict(list)
    arriving: dict[str, list[str]] = defaultdict(list)
    for idx, link_ends in ends.items():
        leaving[link_ends.from_node].append(idx)
        arriving[link_ends.to_node].append(idx)
    unknown_speed = 0
    dangling: list[str] = []
    lanes = {}
    for idx, link in links.items():
        speed_kph = link.number("max_speed")
        if not speed_kph or speed_kph <= 0.0:
            unknown_speed += 1
            speed_kph = DEFAULT_SPEED_LIMIT_KPH
        left = _neighbor(link, "left", links, dangling)
        right = _neighbor(link, "right", links, dangling)
        centerline = _distinct_points(link)
        try:
            lanes[idx] = Lane(
                id=idx,
                centerline=centerline,
                widths=link_widths(link, centerline, stations(centerline), boundaries),
                speed_limit=speed_kph / 3.6,
                successors=tuple(leaving[ends[idx].to_node]),
                predecessors=tuple(arriving[ends[idx].from_node]),
                left_neighbor=left,
                right_neighbor=right,
                is_junction=_inside_junction(ends[idx], nodes),
            )
        except MapGeometryError as error:
            raise link.fail(str(error)) from None
    if unknown_speed:
        notes.append(
            f"link_set.json: {unknown_speed} links without max_speed drive at "
            f"{DEFAULT_SPEED_LIMIT_KPH:g} km/h"
        )
    if dangling:
        notes.append(f"link_set.json: lane-change targets that are not lanes dropped: {dangling}")
    return lanes, ends


def _ends(link: Record, nodes: dict[str, Node] | None) -> LinkEnds:
    from_node, to_node = link.text("from_node_idx"), link.text("to_node_idx")
    if from_node is None or to_node is None:
        raise link.fail("needs from_node_idx and to_node_idx")
    for node in (from_node, to_node):
        if nodes is not None and node not in nodes:
            raise link.fail(f"node {node!r} is not in node_set.json")
    return LinkEnds(from_node, to_node)


def _neighbor(link: Record, side: str, links: dict[str, Record], dangling: list[str]) -> str | None:
    """The lane a car may change into on `side`, when the link allows it."""
    target = link.text(f"{side}_lane_change_dst_link_idx")
    allowed = link.data.get(f"can_move_{side}_lane", True)
    if target is None or allowed is False:
        return None
    if target not in links:
        dangling.append(f"{link.idx}->{target}")
        return None
    return target


def _distinct_points(link: Record) -> FloatArray:
    points = link.points("points")
    step = np.hypot(*np.diff(points[:, :2], axis=0).T)
    points = points[np.concatenate(([True], step > _SAME_POINT_M))]
    if len(points) < 2:
        raise link.fail("points must hold at least two distinct points")
    return points


def _inside_junction(ends: LinkEnds, nodes: dict[str, Node] | None) -> bool:
    """A connector: both its nodes belong to one junction."""
    if nodes is None:
        return False
    return bool(nodes[ends.from_node].junctions & nodes[ends.to_node].junctions)
