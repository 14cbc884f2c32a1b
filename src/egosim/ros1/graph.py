"""The master's getSystemState turned round: per node, what it publishes, subscribes
to and serves (the live view's "ROS nodes" panel, a batch case's wait for its stack)."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Literal, TypeAlias, TypedDict, get_args

SystemState: TypeAlias = tuple[Sequence[object], Sequence[object], Sequence[object]]
"""getSystemState's publishers, subscribers and services: [name, [node, ...]] pairs, as
XML-RPC data (what is not such a pair is passed over)."""
Column = Literal["publishes", "subscribes", "services"]
COLUMNS: tuple[Column, ...] = get_args(Column)


class GraphNode(TypedDict):
    name: str
    publishes: list[str]
    subscribes: list[str]
    services: list[str]


def nodes_of(system_state: SystemState) -> list[GraphNode]:
    """[{name, publishes, subscribes, services}] sorted by node name, names sorted."""
    nodes: dict[str, dict[Column, set[str]]] = {}
    for column, pairs in zip(COLUMNS, system_state, strict=True):
        for pair in pairs:
            name, node_names = _pair(pair)
            for node in node_names:
                entry = nodes.setdefault(node, {c: set() for c in COLUMNS})
                entry[column].add(name)
    return [
        {
            "name": node,
            "publishes": sorted(entry["publishes"]),
            "subscribes": sorted(entry["subscribes"]),
            "services": sorted(entry["services"]),
        }
        for node, entry in sorted(nodes.items())
    ]


def _pair(pair: object) -> tuple[str, list[str]]:
    """A [name, [node, ...]] pair of the reply; no nodes if it is not one."""
    if isinstance(pair, list | tuple) and len(pair) == 2:
        name, nodes = pair
        if isinstance(name, str) and isinstance(nodes, list | tuple):
            return name, [node for node in nodes if isinstance(node, str)]
    return "", []
