"""MGeo nodes: the points where links meet, with their junction and stop-line flags."""

from __future__ import annotations

from dataclasses import dataclass

from egosim.world.map.mgeo.records import Record, unique_by_idx


@dataclass(frozen=True)
class Node:
    idx: str
    junctions: frozenset[str]
    on_stop_line: bool


def read_nodes(items: list[Record]) -> dict[str, Node]:
    nodes = {}
    for idx, record in unique_by_idx(items).items():
        record.point("point")
        nodes[idx] = Node(idx, frozenset(record.ids("junction")), record.flag("on_stop_line"))
    return nodes
