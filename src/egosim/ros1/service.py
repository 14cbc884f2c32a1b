"""TCPROS services (ROS wiki: ROS/TCPROS, "Services"): the server side and the client side.

A response frame is an ok byte, then a length-prefixed body: the serialized response when ok
is 1, or an error string when ok is 0.
"""

from __future__ import annotations

import logging
import socket
import struct
import threading
import time
from collections.abc import Callable, Mapping

from ..logthrottle import LogThrottle
from .connection_header import error_header, read_header, write_header
from .errors import (
    BadRequestError,
    ConnectionClosedError,
    ConnectionRefusedByPeerError,
    MasterError,
    NodeShutdownError,
    ProtocolError,
    ServiceError,
)
from .master_client import MasterClient
from .network import parse_rosrpc_uri
from .tcpros import (
    Limits,
    close_quietly,
    encode_frame,
    recv_exact,
    recv_length_prefixed,
    send_frame,
)
from .types import ServiceTypeInfo

log = logging.getLogger(__name__)
throttle = LogThrottle(log)

ANY_MD5 = "*"
_OK = b"\x01"
_FAILED = b"\x00"
_U32 = struct.Struct("<I")

#: Gets the serialized request and the client's connection header, returns the serialized
#: response; an exception becomes an ok=0 reply carrying its message.
ServiceHandler = Callable[[bytes, Mapping[str, str]], bytes]
#: Chooses the service type served on one connection from the client's header, or raises
#: ConnectionRefusedByPeerError(reason); the handler sees the same header.
ServiceNegotiator = Callable[[Mapping[str, str]], ServiceTypeInfo]


class ServiceServer:
    """A service provided by a node. Create it with ``Node.advertise_service``."""

    def __init__(
        self,
        service: str,
        srv_type: ServiceTypeInfo,
        caller_id: str,
        handler: ServiceHandler,
        *,
        limits: Limits,
        on_close: Callable[[ServiceServer], None] | None = None,
        negotiate: ServiceNegotiator | None = None,
    ) -> None:
        self.service = service
        self.srv_type = srv_type
        self._negotiate = negotiate
        self.caller_id = caller_id
        self.limits = limits
        self._handler = handler
        self._on_close = on_close
        self._lock = threading.Lock()
        self._sockets: set[socket.socket] = set()
        self._closed = False
        self.requests = 0
        self.bytes_received = 0
        self.bytes_sent = 0

    def _reply_header(self, served: ServiceTypeInfo) -> dict[str, str]:
        return {
            "callerid": self.caller_id,
            "service": self.service,
            "type": served.name,
            "md5sum": served.md5sum,
            "request_type": served.request.name,
            "response_type": served.response.name,
        }

    def _choose_type(self, wanted: str, header: Mapping[str, str]) -> ServiceTypeInfo:
        if self._negotiate is not None:
            return self._negotiate(header)
        if wanted not in (ANY_MD5, self.srv_type.md5sum):
            raise ConnectionRefusedByPeerError(
                f"request from [{header['callerid']}]: md5sums do not match: "
                f"[{wanted}] vs. [{self.srv_type.md5sum}]"
            )
        return self.srv_type

    def serve(self, sock: socket.socket, header: Mapping[str, str], peer: str) -> None:
        """Answer a client's connection header, then its requests until it hangs up."""
        wanted = header.get("md5sum")
        if wanted is None or "callerid" not in header:
            reason = "connection header lacks md5sum or callerid"
            log.warning("service %s refused %s: %s", self.service, peer, reason)
            write_header(sock, error_header(reason))
            return
        try:
            served = self._choose_type(wanted, header)
        except ConnectionRefusedByPeerError as exc:
            log.warning("service %s refused %s: %s", self.service, peer, exc.reason)
            write_header(sock, error_header(exc.reason))
            return
        write_header(sock, self._reply_header(served))
        if header.get("probe") == "1":
            return
        with self._lock:
            if self._closed:
                return
            self._sockets.add(sock)
        try:
            self._serve_requests(sock, header)
        finally:
            with self._lock:
                self._sockets.discard(sock)

    def _serve_requests(self, sock: socket.socket, header: Mapping[str, str]) -> None:
        while not self._closed:
            try:
                request = bytes(recv_length_prefixed(sock, self.limits.max_frame_bytes, "request"))
            except ConnectionClosedError as exc:
                if exc.mid_frame:
                    log.warning("service %s: %s from %s", self.service, exc, header["callerid"])
                return
            self.requests += 1
            self.bytes_received += len(request) + 4
            try:
                ok, body = _OK, self._handler(request, header)
            except NodeShutdownError as exc:  # a call that came as the node stops: routine
                log.debug(
                    "service %s: request from %s not served: %s",
                    self.service,
                    header["callerid"],
                    exc,
                )
                ok, body = _FAILED, str(exc).encode()
            except BadRequestError as exc:
                caller = header["callerid"]
                throttle.log(
                    logging.WARNING,
                    (self.service, caller, type(exc).__name__),
                    "service %s: request from %s refused: %s",
                    self.service,
                    caller,
                    exc,
                )
                ok, body = _FAILED, str(exc).encode()
            except Exception as exc:
                throttle.log(
                    logging.ERROR,
                    (self.service, header["callerid"], type(exc).__name__),
                    "service %s handler failed: %s",
                    self.service,
                    exc,
                    exc_info=True,
                )
                ok, body = _FAILED, str(exc).encode()
            # One write for the ok byte and the frame: two small sends would let Nagle's
            # algorithm hold the second back for a delayed ACK (about 40 ms per call).
            sock.sendall(ok + encode_frame(body))
            self.bytes_sent += len(body) + 5
            if header.get("persistent") != "1":
                return

    def close(self) -> None:
        with self._lock:
            if self._closed:
                return
            self._closed = True
            sockets, self._sockets = self._sockets, set()
        for sock in sockets:
            close_quietly(sock)
        if self._on_close is not None:
            self._on_close(self)


class ServiceProxy:
    """Calls a service. Create it with ``Node.service_proxy``."""

    def __init__(
        self,
        service: str,
        srv_type: ServiceTypeInfo,
        master: MasterClient,
        *,
        persistent: bool = False,
        limits: Limits,
    ) -> None:
        self.service = service
        self.srv_type = srv_type
        self.persistent = persistent
        self.limits = limits
        self._master = master
        self._lock = threading.Lock()
        self._sock: socket.socket | None = None
        self._closed = False

    def wait_for_service(self, timeout: float | None = None) -> None:
        """Block until the master knows a provider; ServiceError after ``timeout`` seconds."""
        deadline = None if timeout is None else time.monotonic() + timeout
        while True:
            try:
                self._master.lookup_service(self.service)
                return
            except MasterError as exc:
                if deadline is not None and time.monotonic() >= deadline:
                    raise ServiceError(f"service {self.service} not available: {exc}") from exc
            time.sleep(0.05)

    def _connect(self, timeout: float | None) -> socket.socket:
        try:
            address = parse_rosrpc_uri(self._master.lookup_service(self.service))
        except (MasterError, ValueError) as exc:
            raise ServiceError(f"service {self.service} not available: {exc}") from exc
        sock = socket.create_connection(address, timeout=timeout or self.limits.connect_timeout)
        header = {
            "callerid": self._master.caller_id,
            "service": self.service,
            "md5sum": self.srv_type.md5sum,
            "type": self.srv_type.name,
            "persistent": "1" if self.persistent else "0",
        }
        try:
            write_header(sock, header)
            reply = read_header(sock, self.limits.max_header_bytes)
        except BaseException:
            close_quietly(sock)
            raise
        if "error" in reply:
            close_quietly(sock)
            raise ConnectionRefusedByPeerError(reply["error"])
        sock.settimeout(timeout)
        return sock

    def call(self, request: bytes, timeout: float | None = None) -> bytes:
        """Send one serialized request, return the serialized response.

        ServiceError if the service is unknown, the connection fails, or the handler failed
        (its message is the error string of the reply)."""
        with self._lock:
            if self._closed:
                raise NodeShutdownError(f"proxy of {self.service} is closed")
            sock = self._sock
            try:
                if sock is None:
                    sock = self._connect(timeout)
                send_frame(sock, request)
                ok = recv_exact(sock, 1)
                body = bytes(recv_length_prefixed(sock, self.limits.max_frame_bytes, "response"))
            except ConnectionRefusedByPeerError as exc:
                raise ServiceError(
                    f"service {self.service} refused the call: {exc.reason}"
                ) from exc
            except (OSError, ProtocolError) as exc:
                self._drop(sock)
                raise ServiceError(f"service {self.service} call failed: {exc}") from exc
            if self.persistent:
                self._sock = sock
            else:
                close_quietly(sock)
        if ok != _OK:
            raise ServiceError(body.decode(errors="replace"))
        return body

    def _drop(self, sock: socket.socket | None) -> None:
        if sock is not None:
            close_quietly(sock)
        self._sock = None

    def close(self) -> None:
        with self._lock:
            self._closed = True
            self._drop(self._sock)
