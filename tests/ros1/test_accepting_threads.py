"""A server's accepting threads: each connection served by the thread that accepted it,
a slow connection never holding up the next, the threads a burst needed ending after it,
none left once closed."""

from __future__ import annotations

import socket
import threading
from collections.abc import Iterator

import pytest

from egosim.ros1.accepting_threads import KEEP_ACCEPTING, AcceptingThreads
from tests.ros1.helpers import ListenerOutOfDescriptors
from tests.waiting import until

DEADLINE_S = 30.0
NAME = "accepting test server"


def _threads() -> int:
    return sum(t.name == NAME for t in threading.enumerate())


class EchoOnce:
    """Serves a connection: reads one byte and sends it back, after `release` for b"h"."""

    def __init__(self) -> None:
        self.release = threading.Event()
        self.held = threading.Semaphore(0)

    def __call__(self, sock: socket.socket, address: object) -> None:
        with sock:
            byte = sock.recv(1)
            if byte == b"h":
                self.held.release()
                self.release.wait(DEADLINE_S)
            sock.sendall(byte)


@pytest.fixture
def listener() -> Iterator[socket.socket]:
    with socket.create_server(("127.0.0.1", 0), backlog=16) as sock:
        yield sock


def _ask(listener: socket.socket, byte: bytes) -> socket.socket:
    sock = socket.create_connection(listener.getsockname(), timeout=DEADLINE_S)
    sock.sendall(byte)
    return sock


def test_a_connection_is_served_while_others_are_held(listener: socket.socket) -> None:
    echo = EchoOnce()
    threads = AcceptingThreads(listener, echo, NAME)
    threads.start()
    held = []
    try:
        for k in range(5):
            held.append(_ask(listener, b"h"))
            assert echo.held.acquire(timeout=DEADLINE_S), f"held connection {k} not served"
        with _ask(listener, b"x") as sock:
            assert sock.recv(1) == b"x"
        echo.release.set()
        for sock in held:
            assert sock.recv(1) == b"h"
        until(lambda: _threads() <= KEEP_ACCEPTING, "the burst's extra threads to end")
        with _ask(listener, b"y") as sock:
            assert sock.recv(1) == b"y"
    finally:
        echo.release.set()
        for sock in held:
            sock.close()
        threads.close()
    until(lambda: _threads() == 0, "every thread to end once closed")


def test_closing_leaves_no_thread_in_accept(listener: socket.socket) -> None:
    echo = EchoOnce()
    threads = AcceptingThreads(listener, echo, NAME)
    threads.start()
    with _ask(listener, b"x") as sock:
        assert sock.recv(1) == b"x"
    threads.close()
    address = listener.getsockname()
    listener.close()
    until(lambda: _threads() == 0, "every thread to end once closed")
    with pytest.raises(ConnectionRefusedError):
        socket.create_connection(address, timeout=DEADLINE_S).close()


def test_the_threads_outlive_failing_accepts(listener: socket.socket) -> None:
    failing = ListenerOutOfDescriptors(listener, 3)
    threads = AcceptingThreads(failing, EchoOnce(), NAME)
    threads.start()
    try:
        with _ask(listener, b"x") as sock:
            assert sock.recv(1) == b"x"
        assert failing.failures == 0
    finally:
        threads.close()
