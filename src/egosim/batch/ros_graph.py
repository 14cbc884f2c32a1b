"""Has the stack joined the case's ROS graph? Asked of the case's master over XML-RPC."""

from __future__ import annotations

import http.client
import xmlrpc.client

from egosim.ros1.graph import nodes_of

SIMULATOR_NODE = "/egosim"
NOT_THE_STACK = frozenset({SIMULATOR_NODE, "/master"})
LOG_TOPICS = frozenset({"/rosout", "/rosout_agg"})
CALLER_ID = "/egosim_batch"


def stack_connected(master_uri: str, timeout_s: float = 2.0) -> bool:
    """True once a node other than the simulator publishes or subscribes a topic other
    than the log topics (every rospy node publishes /rosout as it starts)."""
    transport = _TimeoutTransport(timeout_s)
    try:
        reply: object = xmlrpc.client.ServerProxy(master_uri, transport=transport).getSystemState(
            CALLER_ID
        )
    except (OSError, xmlrpc.client.Error):
        return False
    # XML-RPC data, narrowed here: [code, status, [publishers, subscribers, services]]
    if not (isinstance(reply, list | tuple) and len(reply) == 3 and reply[0] == 1):
        return False
    state = reply[2]
    if not (isinstance(state, list | tuple) and len(state) == 3):
        return False
    publishers, subscribers, _ = state
    if not (isinstance(publishers, list | tuple) and isinstance(subscribers, list | tuple)):
        return False
    return any(
        node["name"] not in NOT_THE_STACK
        and any(topic not in LOG_TOPICS for topic in [*node["publishes"], *node["subscribes"]])
        for node in nodes_of((publishers, subscribers, ()))
    )


class _TimeoutTransport(xmlrpc.client.Transport):
    def __init__(self, timeout_s: float) -> None:
        super().__init__()
        self._timeout_s = timeout_s

    def make_connection(self, host: str | tuple[str, dict[str, str]]) -> http.client.HTTPConnection:
        connection = super().make_connection(host)
        connection.timeout = self._timeout_s
        return connection
