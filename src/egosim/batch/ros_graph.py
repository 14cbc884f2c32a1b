"""Has the stack joined the case's ROS graph? Asked of the case's master over XML-RPC."""

from __future__ import annotations

import http.client
import xmlrpc.client
from typing import Any

SIMULATOR_NODE = "/egosim"
NOT_THE_STACK = frozenset({SIMULATOR_NODE, "/master"})
LOG_TOPICS = frozenset({"/rosout", "/rosout_agg"})
CALLER_ID = "/egosim_batch"


def stack_connected(master_uri: str, timeout_s: float = 2.0) -> bool:
    """True once a node other than the simulator publishes or subscribes a topic other
    than the log topics (every rospy node publishes /rosout as it starts)."""
    transport = _TimeoutTransport(timeout_s)
    try:
        # The master's reply is XML-RPC data, untyped by nature.
        reply: Any = xmlrpc.client.ServerProxy(master_uri, transport=transport).getSystemState(
            CALLER_ID
        )
    except (OSError, xmlrpc.client.Error):
        return False
    code, _, state = reply
    if code != 1:
        return False
    publishers, subscribers, _ = state
    return any(
        topic not in LOG_TOPICS and any(node not in NOT_THE_STACK for node in nodes)
        for topic, nodes in [*publishers, *subscribers]
    )


class _TimeoutTransport(xmlrpc.client.Transport):
    def __init__(self, timeout_s: float) -> None:
        super().__init__()
        self._timeout_s = timeout_s

    def make_connection(self, host: str | tuple[str, dict[str, str]]) -> http.client.HTTPConnection:
        connection = super().make_connection(host)
        connection.timeout = self._timeout_s
        return connection
