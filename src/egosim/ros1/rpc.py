"""XML-RPC plumbing shared by the master and slave APIs: a threaded server and timed calls."""

from __future__ import annotations

import http.client
import logging
import socket
import threading
import xmlrpc.client
from collections.abc import Callable
from enum import IntEnum
from typing import TYPE_CHECKING, Any
from urllib.parse import urlsplit
from xmlrpc.server import SimpleXMLRPCServer

from .accepting_threads import AcceptingThreads
from .errors import PeerUnreachableError
from .rpc_handler import RequestHandler

if TYPE_CHECKING:
    from _typeshed import ReadableBuffer

log = logging.getLogger(__name__)


class StatusCode(IntEnum):
    """The code that opens every master and slave API reply ``[code, statusMessage, value]``."""

    ERROR = -1
    """The call is wrong (bad arguments, unknown name); the value is not meaningful."""
    FAILURE = 0
    """The call was valid but did not succeed."""
    SUCCESS = 1


# A master or slave API reply: [code, statusMessage, value].
Reply = list[Any]


def reply(code: StatusCode, message: str, value: Any) -> Reply:
    """An API reply; the code goes out as a plain int, the only kind XML-RPC marshals."""
    return [int(code), message, value]


IN_PROCESS = ("this process", 0)
"""The peer address of a call made in the server's own process."""


class _TimeoutTransport(xmlrpc.client.Transport):
    def __init__(self, timeout: float) -> None:
        super().__init__()
        self._timeout = timeout

    def make_connection(self, host: Any) -> http.client.HTTPConnection:
        conn = super().make_connection(host)
        conn.timeout = self._timeout
        return conn


def call(uri: str, method: str, *args: Any, timeout: float = 5.0) -> Any:
    """Call ``method`` on the XML-RPC server at ``uri``; a fresh connection keeps it thread-safe.
    A server of this process (an embedded master, for one) is handed the request's bytes
    directly, without a socket, a thread or HTTP: the same call and reply, the same
    marshalling, in a fraction of the time.

    Raises PeerUnreachableError when nothing answers (refused, reset, timed out).
    """
    server = _in_process(uri)
    if server is not None:
        # Marshalled as ServerProxy marshals (its defaults): the same values, the same errors.
        reply_body = server.answer_in_process(xmlrpc.client.dumps(args, method))
        return xmlrpc.client.loads(reply_body)[0][0]
    proxy = xmlrpc.client.ServerProxy(uri, transport=_TimeoutTransport(timeout))
    try:
        return getattr(proxy, method)(*args)
    except (OSError, http.client.HTTPException) as exc:
        raise PeerUnreachableError(f"no XML-RPC answer from {uri} to {method}: {exc}") from exc
    finally:
        proxy("close")()


_serving: dict[tuple[str, int], XmlRpcServer] = {}
"""This process's servers while they serve, by the host and port they are bound to."""
_serving_lock = threading.Lock()


def _in_process(uri: str) -> XmlRpcServer | None:
    parts = urlsplit(uri)
    try:
        address = (parts.hostname or "", parts.port or 0)
    except ValueError:  # not a port: the network call says what is wrong
        return None
    with _serving_lock:
        return _serving.get(address)


class XmlRpcServer(SimpleXMLRPCServer):
    """Serves one handler object's public methods, each connection in the thread that
    accepted it (accepting_threads), its request read and answered by rpc_handler."""

    allow_reuse_address = True
    # socketserver's default backlog of 5 resets connections when many nodes start at once.
    request_queue_size = 128

    def __init__(self, address: tuple[str, int], name: str) -> None:
        self.peer = threading.local()
        self._name = name
        super().__init__(address, requestHandler=RequestHandler, logRequests=False)
        self.register_multicall_functions()
        self._address = (str(self.server_address[0]), self.port)
        self._threads = AcceptingThreads(self.socket, self._serve_connection, name)

    @property
    def port(self) -> int:
        return self.server_address[1]

    def register_api(self, functions: dict[str, Callable[..., Any]]) -> None:
        for method, function in functions.items():
            self.register_function(function, method)

    def start(self) -> None:
        self._threads.start()
        with _serving_lock:
            _serving[self._address] = self

    def stop(self) -> None:
        with _serving_lock:
            if _serving.get(self._address) is self:
                del _serving[self._address]
        self._threads.close()
        self.server_close()

    def _serve_connection(self, request: socket.socket, client_address: object) -> None:
        # As socketserver's threading servers serve a connection.
        try:
            self.finish_request(request, client_address)
        except Exception:
            self.handle_error(request, client_address)
        finally:
            self.shutdown_request(request)

    def answer(self, request: str | bytes, peer: object) -> bytes:
        """The encoded reply to an XML-RPC request from `peer` (its address)."""
        self.peer.address = peer
        return self._marshaled_dispatch(request)

    def answer_in_process(self, request: str) -> bytes:
        """The reply to an XML-RPC request made in this process, as a peer would get it."""
        return self.answer(request, IN_PROCESS)

    # typeshed declares str, but CPython's dispatcher returns the encoded body (bytes),
    # which is what the request handler writes.
    def _marshaled_dispatch(  # type: ignore[override]
        self, data: str | ReadableBuffer, dispatch_method: Any = None, path: Any = None
    ) -> bytes:
        try:
            params, method = xmlrpc.client.loads(data, use_builtin_types=self.use_builtin_types)
        except Exception as exc:
            self._log_bad_request(f"request is not XML-RPC: {exc}")
            return _fault(f"request is not XML-RPC: {exc}")
        if method is None:
            self._log_bad_request("request is a methodResponse, not a methodCall")
            return _fault("request is a methodResponse, not a methodCall")
        try:
            response = self._dispatch(method, params)
            return xmlrpc.client.dumps(
                (response,), methodresponse=True, allow_none=self.allow_none, encoding=self.encoding
            ).encode(self.encoding, "xmlcharrefreplace")
        except Exception as exc:
            self._log_bad_request(f"{method}{_short(params)} failed: {exc!r}")
            return _fault(f"{type(exc).__name__}: {exc}")

    def _log_bad_request(self, what: str) -> None:
        log.warning("%s: XML-RPC from %s: %s", self._name, getattr(self.peer, "address", "?"), what)


def _fault(message: str) -> bytes:
    return xmlrpc.client.dumps(xmlrpc.client.Fault(1, message), methodresponse=True).encode()


def _short(params: tuple[Any, ...]) -> str:
    text = repr(params)
    return text if len(text) < 200 else text[:200] + "...)"
