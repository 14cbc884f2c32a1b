"""Fixtures of the ros1 tests: egosim nodes that are always shut down."""

from __future__ import annotations

from collections.abc import Callable, Iterator
from typing import Any

import pytest

from egosim.ros1 import Node


@pytest.fixture
def make_node() -> Iterator[Callable[..., Node]]:
    """``make_node(name, **Node kwargs)``; every node is shut down at teardown."""
    nodes: list[Node] = []

    def make(name: str, **kwargs: Any) -> Node:
        kwargs.setdefault("env", {})
        kwargs.setdefault("rosout_logger", None)
        node = Node(name, **kwargs)
        nodes.append(node)
        return node

    try:
        yield make
    finally:
        for node in nodes:
            node.shutdown("test teardown")
