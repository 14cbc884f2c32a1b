"""Small helpers for the ros1 tests."""

from __future__ import annotations

import errno
import json
import socket
import threading
import time
from collections.abc import Callable
from pathlib import Path

from egosim.msgs import MessageType, ServiceType, get_profile
from egosim.ros1 import Node, Publisher, rpc
from egosim.ros1.connection_header import read_header, write_header
from egosim.ros1.tcpros import recv_length_prefixed
from tests.conftest import EVENT_TIMEOUT_S, RosProcess

PEERS = Path(__file__).parent / "peers"
PROFILE = get_profile("26.r1")
STRING = PROFILE.message("std_msgs/String")


def peer(script: str) -> str:
    return str(PEERS / script)


def drain(sock: socket.socket) -> bytes:
    """Half-close, then read what the server answers until it hangs up (a reset counts:
    a server closing on unread input resets the connection)."""
    chunks = []
    try:
        sock.shutdown(socket.SHUT_WR)
        while chunk := sock.recv(65536):
            chunks.append(chunk)
    except (ConnectionResetError, BrokenPipeError, OSError):
        pass
    return b"".join(chunks)


def send_raw(address: tuple[str, int], data: bytes) -> bytes:
    with socket.create_connection(address, timeout=EVENT_TIMEOUT_S) as sock:
        try:
            sock.sendall(data)
        except (ConnectionResetError, BrokenPipeError):
            return b""
        return drain(sock)


def uri_address(uri: str) -> tuple[str, int]:
    host, port = uri.removeprefix("http://").rstrip("/").split(":")
    return host, int(port)


def wait_until(condition: Callable[[], object], timeout: float = EVENT_TIMEOUT_S) -> None:
    """Poll ``condition`` until true; fail the test if it never becomes true."""
    deadline = time.monotonic() + timeout
    while not condition():
        if time.monotonic() > deadline:
            raise AssertionError(f"condition never became true: {condition}")
        time.sleep(0.01)


def string_bytes(text: str) -> bytes:
    return STRING.serialize(STRING.new(data=text))


def string_text(data: bytes) -> str:
    return STRING.deserialize(data).data


def next_json(process: RosProcess, key: str) -> dict:
    """The next JSON line printed by a peer that has ``key``."""
    return json.loads(process.expect(rf'^\{{"{key}"').string)


def write_definition(tmp_path: Path, msg_type: MessageType) -> str:
    path = tmp_path / (msg_type.name.replace("/", "_") + ".msg")
    path.write_text(msg_type.definition)
    return str(path)


def write_service_spec(tmp_path: Path, srv_type: ServiceType) -> str:
    spec = {
        "name": srv_type.name,
        "md5sum": srv_type.md5sum,
        "request": {"name": srv_type.request.name, "definition": srv_type.request.definition},
        "response": {"name": srv_type.response.name, "definition": srv_type.response.definition},
    }
    path = tmp_path / (srv_type.name.replace("/", "_") + ".json")
    path.write_text(json.dumps(spec))
    return str(path)


class Publishing:
    """Publishes ``make()`` on ``publisher`` at about ``rate_hz`` on a thread, inside a with."""

    def __init__(self, publisher: Publisher, make: Callable[[int], bytes], rate_hz: float) -> None:
        self._publisher = publisher
        self._make = make
        self._period = 1.0 / rate_hz
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)
        self.count = 0

    def _run(self) -> None:
        while not self._stop.wait(self._period):
            self._publisher.publish(self._make(self.count))
            self.count += 1

    def __enter__(self) -> Publishing:
        self._thread.start()
        return self

    def __exit__(self, *exc: object) -> None:
        self._stop.set()
        self._thread.join()


def raw_connect(node: Node, fields: dict[str, str]) -> tuple[socket.socket, dict[str, str]]:
    """Connect a bare socket to ``node``'s TCPROS server, send ``fields``, read the reply."""
    sock = socket.create_connection(node.tcpros_address, timeout=EVENT_TIMEOUT_S)
    write_header(sock, fields)
    return sock, read_header(sock, 1 << 20)


def raw_subscribe(
    node: Node, topic: str, md5sum: str, type_name: str = "*", callerid: str = "/raw"
) -> tuple[socket.socket, dict[str, str]]:
    return raw_connect(
        node, {"callerid": callerid, "topic": topic, "md5sum": md5sum, "type": type_name}
    )


def read_frame(sock: socket.socket) -> bytes:
    return bytes(recv_length_prefixed(sock, 1 << 26))


def slave_call(node: Node, method: str, *args: object) -> list:
    return rpc.call(node.uri, method, "/test", *args)


class ListenerOutOfDescriptors:
    """A listening socket whose first accepts fail as when the process has no fds left."""

    def __init__(self, real: socket.socket, failures: int) -> None:
        self._real = real
        self.failures = failures

    def accept(self) -> tuple[socket.socket, object]:
        if self.failures:
            self.failures -= 1
            raise OSError(errno.EMFILE, "Too many open files")
        return self._real.accept()

    def __getattr__(self, name: str) -> object:
        return getattr(self._real, name)
