"""Threads that accept a listening socket's connections, each serving the connection it
accepted.

A server whose one thread accepts and hands each connection to another pays, for every
connection, for waking both (its select, the hand-over, the two taking turns at the
GIL): for a connection that carries one small request, as every XML-RPC client's does,
that is a sixth of the server's CPU (docs/BENCHMARKS.md). Here the threads wait in
accept() themselves and the kernel wakes one per connection, which serves it: nothing is
handed over. Whenever the last waiting thread takes a connection, another starts
accepting (from handler_threads: one whose serving ended, if one waits), so a connection
never waits for a slow one to end. A thread that has served accepts again, unless
KEEP_ACCEPTING others already do.
"""

from __future__ import annotations

import contextlib
import socket
import threading
import time
from collections.abc import Callable

from .handler_threads import HandlerThreads

KEEP_ACCEPTING = 2
"""Threads kept waiting in accept() between connections: with two, the one a connection
wakes leaves another waiting and needs no helper, however fast connections follow."""

ACCEPT_RETRY_S = 0.1
"""Pause before accepting again after accept() failed (out of file descriptors, say)."""

CLOSE_WAIT_S = 2.0
"""How long close() waits for the threads to leave accept()."""

Serve = Callable[[socket.socket, object], None]
"""Serves one accepted connection (the socket and the peer's address) and closes it."""


class AcceptingThreads:
    def __init__(self, listener: socket.socket, serve: Serve, name: str) -> None:
        self._listener = listener
        self._serve = serve
        self._name = name
        self._threads = HandlerThreads()
        self._lock = threading.Lock()
        self._left = threading.Condition(self._lock)
        self._accepting = 0
        """Threads in accept(), or started or called back to go there."""
        self._closed = False

    def start(self) -> None:
        with self._lock:
            self._accepting += KEEP_ACCEPTING
        for _ in range(KEEP_ACCEPTING):
            self._threads.run(self._accept_and_serve, self._name)

    def close(self) -> None:
        """No connection is accepted from now on. Returns once no thread is left in
        accept(), so the listener can be closed without another socket taking its
        descriptor under a thread about to accept."""
        with self._lock:
            self._closed = True
        with contextlib.suppress(OSError):
            # On Linux this wakes the threads in accept() (as the TCPROS listener's close).
            self._listener.shutdown(socket.SHUT_RDWR)
        with self._lock:
            self._left.wait_for(lambda: self._accepting == 0, timeout=CLOSE_WAIT_S)
        self._threads.close()

    def _accept_and_serve(self) -> None:
        while True:
            try:
                sock, address = self._listener.accept()
            except OSError:
                if self._closed:
                    with self._lock:
                        self._accepting -= 1
                        self._left.notify_all()
                    return
                time.sleep(ACCEPT_RETRY_S)  # the listener is still good: try again
                continue
            with self._lock:
                self._accepting -= 1
                helper = self._accepting == 0 and not self._closed
                if helper:
                    self._accepting += 1
            if helper:
                self._threads.run(self._accept_and_serve, self._name)
            self._serve(sock, address)
            with self._lock:
                if self._closed or self._accepting >= KEEP_ACCEPTING:
                    return
                self._accepting += 1
