"""The one TCP server of a node that accepts TCPROS connections for its topics and services.

Each accepted connection gets a thread (handler_threads: one whose last connection ended, if
one waits) that reads the connection header (bounded in size and time) and hands the
socket to whoever serves the named topic or service.
"""

from __future__ import annotations

import functools
import logging
import socket
import threading
import time
from collections.abc import Callable, Mapping
from typing import cast

from .connection_header import read_header
from .errors import ProtocolError
from .handler_threads import HandlerThreads
from .tcpros import Limits, close_quietly

log = logging.getLogger(__name__)

#: Pause before accepting again after accept() failed (e.g. out of file descriptors), s.
ACCEPT_RETRY_S = 0.1

#: Serves one connection; returns True if it took the socket over (and will close it).
Dispatch = Callable[[socket.socket, Mapping[str, str], str], bool]


class TcprosServer:
    def __init__(self, bind_host: str, dispatch: Dispatch, limits: Limits) -> None:
        self._dispatch = dispatch
        self._limits = limits
        self._listener = socket.create_server((bind_host, 0), backlog=128)
        self._lock = threading.Lock()
        self._pending: set[socket.socket] = set()
        self._closed = False
        self._handlers = HandlerThreads()
        self._thread = threading.Thread(target=self._accept, name="tcpros accept", daemon=True)
        self._thread.start()

    @property
    def port(self) -> int:
        return cast(int, self._listener.getsockname()[1])

    def _accept(self) -> None:
        failing = False
        while True:
            try:
                sock, address = self._listener.accept()
            except OSError as exc:
                if self._closed:
                    return
                # Out of file descriptors, or a connection reset while queued: the
                # listener is still good, so keep serving once the moment has passed.
                if not failing:
                    log.error("TCPROS listener: accept failed (%s); retrying", exc)
                failing = True
                time.sleep(ACCEPT_RETRY_S)
                continue
            if failing:
                log.warning("TCPROS listener: accepting connections again")
                failing = False
            peer = f"{address[0]}:{address[1]}"
            with self._lock:
                if self._closed:
                    sock.close()
                    return
                self._pending.add(sock)
            self._handlers.run(functools.partial(self._handle, sock, peer), f"tcpros from {peer}")

    def _handle(self, sock: socket.socket, peer: str) -> None:
        keep = False
        try:
            sock.settimeout(self._limits.header_timeout)
            header = read_header(sock, self._limits.max_header_bytes)
            sock.settimeout(None)
            keep = self._dispatch(sock, header, peer)
        except ProtocolError as exc:
            if not self._closed:
                log.warning("TCPROS peer %s: %s", peer, exc)
        except OSError as exc:  # reset, broken pipe: the peer went away
            if not self._closed:
                log.debug("TCPROS peer %s: %s", peer, exc)
        finally:
            with self._lock:
                self._pending.discard(sock)
            if not keep:
                close_quietly(sock)

    def close(self) -> None:
        with self._lock:
            self._closed = True
            pending, self._pending = self._pending, set()
        close_quietly(self._listener)
        for sock in pending:
            close_quietly(sock)
        self._thread.join(timeout=2.0)
        self._handlers.close()
