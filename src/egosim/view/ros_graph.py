"""The master's getSystemState turned round: per node, what it publishes, subscribes
to and serves, for the page's "ROS nodes" panel."""

from __future__ import annotations

from typing import Any


def nodes_of(system_state: tuple[list[Any], list[Any], list[Any]]) -> list[dict[str, Any]]:
    """[{name, publishes, subscribes, services}] sorted by node name, names sorted."""
    nodes: dict[str, dict[str, set[str]]] = {}
    for column, (name_lists) in zip(
        ("publishes", "subscribes", "services"), system_state, strict=True
    ):
        for name, node_names in name_lists:
            for node in node_names:
                entry = nodes.setdefault(
                    node, {"publishes": set(), "subscribes": set(), "services": set()}
                )
                entry[column].add(name)
    return [
        {"name": node, **{column: sorted(names) for column, names in entry.items()}}
        for node, entry in sorted(nodes.items())
    ]
