"""The subscribing side of a TCPROS topic (ROS wiki: ROS/TCPROS, "Topics"; Slave_API,
requestTopic and publisherUpdate).

One connection thread per publisher: it asks the publisher's slave API for a TCPROS
endpoint, sends our header, checks the answer and hands each frame to the callback.
Lost connections are retried while the master still lists the publisher.
"""

from __future__ import annotations

import logging
import socket
import threading
import xmlrpc.client
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass

from . import rpc
from .connection_header import read_header, write_header
from .errors import (
    ConnectionClosedError,
    ConnectionRefusedByPeerError,
    ProtocolError,
    Ros1Error,
)
from .tcpros import Limits, close_quietly, recv_length_prefixed, set_nodelay
from .types import MessageTypeInfo

log = logging.getLogger(__name__)

#: Receives the serialized message and the publisher's connection header (its md5sum,
#: type, callerid...), so that upper layers can decode by md5.
MessageCallback = Callable[[bytes, Mapping[str, str]], None]

_RETRY_FIRST_S = 0.1
_RETRY_MAX_S = 2.0


@dataclass
class InboundStats:
    connection_id: int
    publisher_uri: str
    bytes_received: int = 0
    messages_received: int = 0
    connected: bool = False
    publisher_id: str = ""


class _Inbound:
    """The connection to one publisher, with its reader thread."""

    def __init__(self, subscriber: Subscriber, publisher_uri: str, connection_id: int) -> None:
        self._sub = subscriber
        self.stats = InboundStats(connection_id, publisher_uri, publisher_id=publisher_uri)
        self._stop = threading.Event()
        self._sock: socket.socket | None = None
        self._lock = threading.Lock()
        self._thread = threading.Thread(
            target=self._run, name=f"tcpros in {subscriber.topic} <- {publisher_uri}", daemon=True
        )
        self._thread.start()

    def close(self) -> None:
        self._stop.set()
        with self._lock:
            if self._sock is not None:
                close_quietly(self._sock)

    def _run(self) -> None:
        delay = _RETRY_FIRST_S
        while not self._stop.is_set():
            try:
                self._connect_and_read()
                delay = _RETRY_FIRST_S
            except ConnectionRefusedByPeerError as exc:
                log.warning(
                    "publisher %s refused %s: %s",
                    self.stats.publisher_uri,
                    self._sub.topic,
                    exc.reason,
                )
                return
            except ConnectionClosedError as exc:
                if not self._stop.is_set():
                    # A publisher that served us and ends between messages (a rostopic
                    # pub -1 done) is routine; one that hangs up before or mid-message is not.
                    routine = self.stats.connected and not exc.mid_frame
                    log.log(
                        logging.DEBUG if routine else logging.INFO,
                        "publisher %s of %s left: %s",
                        self.stats.publisher_uri,
                        self._sub.topic,
                        exc,
                    )
            except ProtocolError as exc:
                if not self._stop.is_set():
                    log.warning(
                        "publisher %s of %s: %s", self.stats.publisher_uri, self._sub.topic, exc
                    )
            except (Ros1Error, OSError, xmlrpc.client.Error) as exc:
                if not self._stop.is_set():
                    log.info(
                        "publisher %s of %s: %s", self.stats.publisher_uri, self._sub.topic, exc
                    )
            finally:
                self.stats.connected = False
            if self._stop.wait(delay):
                return
            delay = min(delay * 2, _RETRY_MAX_S)

    def _request_topic(self) -> tuple[str, int]:
        reply = rpc.call(
            self.stats.publisher_uri,
            "requestTopic",
            self._sub.caller_id,
            self._sub.topic,
            [["TCPROS"]],
            timeout=self._sub.limits.connect_timeout,
        )
        try:
            code, message, protocol = reply
            if code != rpc.StatusCode.SUCCESS or not protocol or protocol[0] != "TCPROS":
                raise ProtocolError(f"requestTopic refused: {message}")
            host, port = protocol[1], int(protocol[2])
        except (TypeError, ValueError, IndexError) as exc:
            # A malformed reply is a failed attempt like any other: retried, not fatal.
            raise ProtocolError(f"malformed requestTopic reply {reply!r}") from exc
        if not isinstance(host, str) or not 0 < port < 65536:
            raise ProtocolError(f"requestTopic reply names no address: {reply!r}")
        return host, port

    def _connect_and_read(self) -> None:
        limits = self._sub.limits
        address = self._request_topic()
        sock = socket.create_connection(address, timeout=limits.connect_timeout)
        with self._lock:
            if self._stop.is_set():
                sock.close()
                return
            self._sock = sock
        try:
            if self._sub.tcp_nodelay:
                set_nodelay(sock)
            write_header(sock, self._sub.header())
            header = read_header(sock, limits.max_header_bytes)
            if "error" in header:
                raise ConnectionRefusedByPeerError(header["error"])
            sock.settimeout(None)
            self.stats.connected = True
            self.stats.publisher_id = header.get("callerid", self.stats.publisher_uri)
            while not self._stop.is_set():
                data = bytes(recv_length_prefixed(sock, limits.max_frame_bytes))
                self.stats.bytes_received += len(data) + 4
                self.stats.messages_received += 1
                self._sub.deliver(data, header)
        finally:
            close_quietly(sock)


class Subscriber:
    """A topic subscription of a node. Create it with ``Node.subscribe``."""

    def __init__(
        self,
        topic: str,
        msg_type: MessageTypeInfo,
        caller_id: str,
        callback: MessageCallback,
        *,
        limits: Limits,
        tcp_nodelay: bool = False,
        next_connection_id: Callable[[], int],
        on_close: Callable[[Subscriber], None] | None = None,
    ) -> None:
        self.topic = topic
        self.msg_type = msg_type
        self.caller_id = caller_id
        self.limits = limits
        self.tcp_nodelay = tcp_nodelay
        self._callback = callback
        self._next_connection_id = next_connection_id
        self._on_close = on_close
        self._lock = threading.Lock()
        self._inbound: dict[str, _Inbound] = {}
        self._closed = False

    def header(self) -> dict[str, str]:
        return {
            "callerid": self.caller_id,
            "topic": self.topic,
            "type": self.msg_type.name,
            "md5sum": self.msg_type.md5sum,
            "message_definition": self.msg_type.definition,
            "tcp_nodelay": "1" if self.tcp_nodelay else "0",
        }

    @property
    def connections(self) -> list[InboundStats]:
        with self._lock:
            return [inbound.stats for inbound in self._inbound.values()]

    @property
    def num_publishers(self) -> int:
        return sum(1 for stats in self.connections if stats.connected)

    def deliver(self, data: bytes, header: Mapping[str, str]) -> None:
        try:
            self._callback(data, header)
        except Exception:
            log.exception("callback of subscriber to %s failed", self.topic)

    def update_publishers(self, publisher_uris: Iterable[str]) -> None:
        """Connect to publishers not yet known and drop those no longer listed."""
        wanted = set(publisher_uris)
        with self._lock:
            if self._closed:
                return
            gone = [self._inbound.pop(uri) for uri in list(self._inbound) if uri not in wanted]
            for uri in wanted - self._inbound.keys():
                self._inbound[uri] = _Inbound(self, uri, self._next_connection_id())
        for inbound in gone:
            inbound.close()

    def close(self) -> None:
        """Disconnect from all publishers and unregister from the master."""
        with self._lock:
            if self._closed:
                return
            self._closed = True
            inbound, self._inbound = list(self._inbound.values()), {}
        for connection in inbound:
            connection.close()
        if self._on_close is not None:
            self._on_close(self)
