"""TCPROS framing (ROS wiki: ROS/TCPROS): length-prefixed frames over a stream socket."""

from __future__ import annotations

import contextlib
import socket
import struct
from collections.abc import Sequence
from dataclasses import dataclass

from .errors import ConnectionClosedError, FrameTooLargeError

_U32 = struct.Struct("<I")
#: Payloads below this size are copied into one buffer with their length prefixes; larger
#: ones are written from where they are.
_JOINED_MAX = 64 * 1024


@dataclass(frozen=True)
class Limits:
    """Bounds on what a peer may make us allocate or wait for."""

    max_header_bytes: int = 64 * 1024
    max_frame_bytes: int = 64 * 1024 * 1024
    #: how long a freshly accepted peer may take to send its connection header (s)
    header_timeout: float = 10.0
    #: how long to wait for a peer's TCP connect or XML-RPC answer (s)
    connect_timeout: float = 5.0


def recv_exact(sock: socket.socket, size: int) -> bytearray:
    """Read exactly ``size`` bytes; ConnectionClosedError if the peer closes first."""
    buf = bytearray(size)
    view = memoryview(buf)
    got = 0
    while got < size:
        n = sock.recv_into(view[got:], size - got)
        if n == 0:
            raise ConnectionClosedError(
                f"peer closed the connection after {got} of {size} bytes", mid_frame=got > 0
            )
        got += n
    return buf


def recv_length_prefixed(sock: socket.socket, max_bytes: int, what: str = "frame") -> bytearray:
    """Read a uint32 little-endian length then that many bytes, refusing absurd lengths."""
    (size,) = _U32.unpack(recv_exact(sock, 4))
    if size > max_bytes:
        raise FrameTooLargeError(f"{what} length {size} exceeds the limit of {max_bytes} bytes")
    try:
        return recv_exact(sock, size)
    except ConnectionClosedError as exc:
        raise ConnectionClosedError(f"{what}: {exc}", mid_frame=True) from None


def encode_frame(data: bytes | memoryview) -> bytes:
    return _U32.pack(len(data)) + bytes(data)


def encode_frames(payloads: Sequence[bytes]) -> bytes:
    """`payloads` as consecutive frames in one buffer, each payload copied once."""
    parts: list[bytes] = []
    for data in payloads:
        parts.append(_U32.pack(len(data)))
        parts.append(data)
    return b"".join(parts)


def send_frame(sock: socket.socket, data: bytes | memoryview) -> None:
    """Send a length prefix and ``data`` without concatenating them (large payloads)."""
    if len(data) < _JOINED_MAX:
        sock.sendall(encode_frame(data))
        return
    chunks = [memoryview(_U32.pack(len(data))), memoryview(data)]
    while chunks:
        sent = sock.sendmsg(chunks)
        while chunks and sent >= len(chunks[0]):
            sent -= len(chunks[0])
            chunks.pop(0)
        if chunks and sent:
            chunks[0] = chunks[0][sent:]


def send_frames(sock: socket.socket, payloads: Sequence[bytes]) -> None:
    """Send `payloads` as frames, in order: runs of small ones joined into one write, large
    ones as send_frame sends them."""
    run: list[bytes] = []
    run_size = 0
    for data in payloads:
        if len(data) >= _JOINED_MAX:
            if run:
                sock.sendall(encode_frames(run))
                run, run_size = [], 0
            send_frame(sock, data)
            continue
        run.append(data)
        run_size += len(data)
        if run_size >= _JOINED_MAX:
            sock.sendall(encode_frames(run))
            run, run_size = [], 0
    if run:
        sock.sendall(encode_frames(run))


def set_nodelay(sock: socket.socket, enabled: bool = True) -> None:
    sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1 if enabled else 0)


def close_quietly(sock: socket.socket) -> None:
    with contextlib.suppress(OSError):
        sock.shutdown(socket.SHUT_RDWR)
    sock.close()
