"""The Slave API every node serves over XML-RPC (ROS wiki: Slave_API).

Replies are ``[code, statusMessage, value]`` like the master's.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from typing import Any, Protocol

from .publication import Publisher
from .rpc import Reply, StatusCode, reply
from .service import ServiceServer
from .subscription import Subscriber

TCPROS = "TCPROS"

#: XML-RPC integers are 32-bit; byte counters of a long run saturate here rather than fault.
_XMLRPC_INT_MAX = 2**31 - 1


def _count(value: int) -> int:
    return min(value, _XMLRPC_INT_MAX)


class SlaveNode(Protocol):
    """What the Slave API reads and does of its node (ros1/node.py's Node)."""

    @property
    def master_uri(self) -> str: ...

    @property
    def tcpros_address(self) -> tuple[str, int]: ...

    @property
    def publishers(self) -> list[Publisher]: ...

    @property
    def subscribers(self) -> list[Subscriber]: ...

    @property
    def services(self) -> list[ServiceServer]: ...

    def publisher(self, topic: str) -> Publisher | None: ...

    def publishers_updated(self, topic: str, publisher_uris: list[str]) -> None: ...

    def param_updated(self, key: str, value: Any) -> None: ...

    def request_shutdown(self, reason: str) -> None: ...


class SlaveApi:
    def __init__(self, node: SlaveNode) -> None:
        self._node = node

    def functions(self) -> dict[str, Callable[..., Reply]]:
        return {
            "getBusStats": self.get_bus_stats,
            "getBusInfo": self.get_bus_info,
            "getMasterUri": self.get_master_uri,
            "shutdown": self.shutdown,
            "getPid": self.get_pid,
            "getSubscriptions": self.get_subscriptions,
            "getPublications": self.get_publications,
            "paramUpdate": self.param_update,
            "publisherUpdate": self.publisher_update,
            "requestTopic": self.request_topic,
        }

    def get_bus_stats(self, caller_id: str) -> Reply:
        """Publish stats are ``[topic, messagesPublished, [[connectionId, bytesSent, numSent,
        connected, numDropped]]]``: numDropped (oldest messages dropped because the subscriber
        did not keep up) extends the spec's tuple. Subscribe stats follow the spec, with a drop
        estimate of -1 (unknown). Service stats: ``[numRequests, bytesReceived, bytesSent]``."""
        node = self._node
        publish = [
            [
                pub.topic,
                _count(pub.messages_published),
                [
                    [
                        c.connection_id,
                        _count(c.bytes_sent),
                        _count(c.messages_sent),
                        c.connected,
                        _count(c.dropped),
                    ]
                    for c in pub.connections
                ],
            ]
            for pub in node.publishers
        ]
        subscribe = [
            [
                sub.topic,
                [
                    [c.connection_id, _count(c.bytes_received), -1, c.connected]
                    for c in sub.connections
                ],
            ]
            for sub in node.subscribers
        ]
        services = node.services
        service = [
            _count(sum(s.requests for s in services)),
            _count(sum(s.bytes_received for s in services)),
            _count(sum(s.bytes_sent for s in services)),
        ]
        return reply(StatusCode.SUCCESS, "", [publish, subscribe, service])

    def get_bus_info(self, caller_id: str) -> Reply:
        node = self._node
        info: list[list[Any]] = []
        for pub in node.publishers:
            for out in pub.connections:
                info.append(
                    [out.connection_id, out.peer, "o", TCPROS, pub.topic, out.connected, ""]
                )
        for sub in node.subscribers:
            for inbound in sub.connections:
                info.append(
                    [
                        inbound.connection_id,
                        inbound.publisher_id,
                        "i",
                        TCPROS,
                        sub.topic,
                        inbound.connected,
                        "",
                    ]
                )
        return reply(StatusCode.SUCCESS, "bus info", info)

    def get_master_uri(self, caller_id: str) -> Reply:
        return reply(StatusCode.SUCCESS, "", self._node.master_uri)

    def shutdown(self, caller_id: str, msg: str = "") -> Reply:
        reason = f"requested by {caller_id}: {msg}" if msg else f"requested by {caller_id}"
        self._node.request_shutdown(reason)
        return reply(StatusCode.SUCCESS, "shutdown", 0)

    def get_pid(self, caller_id: str) -> Reply:
        return reply(StatusCode.SUCCESS, "", os.getpid())

    def get_subscriptions(self, caller_id: str) -> Reply:
        topics = [[s.topic, s.msg_type.name] for s in self._node.subscribers]
        return reply(StatusCode.SUCCESS, "subscriptions", topics)

    def get_publications(self, caller_id: str) -> Reply:
        topics = [[p.topic, p.msg_type.name] for p in self._node.publishers]
        return reply(StatusCode.SUCCESS, "publications", topics)

    def param_update(self, caller_id: str, parameter_key: str, parameter_value: Any) -> Reply:
        self._node.param_updated(parameter_key, parameter_value)
        return reply(StatusCode.SUCCESS, "", 0)

    def publisher_update(self, caller_id: str, topic: str, publishers: list[str]) -> Reply:
        if not isinstance(publishers, list) or not all(isinstance(p, str) for p in publishers):
            # The update replaces the topic's publishers: a malformed one must change nothing.
            return reply(
                StatusCode.ERROR,
                f"publishers must be a list of XML-RPC URIs, got {publishers!r}",
                0,
            )
        self._node.publishers_updated(topic, publishers)
        return reply(StatusCode.SUCCESS, "", 0)

    def request_topic(self, caller_id: str, topic: str, protocols: list[Any]) -> Reply:
        if self._node.publisher(topic) is None:
            return reply(StatusCode.ERROR, f"not a publisher of [{topic}]", [])
        if not any(p and p[0] == TCPROS for p in protocols):
            return reply(StatusCode.FAILURE, "no supported protocol implementations", [])
        host, port = self._node.tcpros_address
        return reply(StatusCode.SUCCESS, f"ready on {host}:{port}", [TCPROS, host, port])
