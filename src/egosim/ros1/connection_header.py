"""TCPROS connection header (ROS wiki: ROS/Connection Header).

A header is a little-endian uint32 total length followed by fields, each a uint32 length
and ``key=value`` bytes.
"""

from __future__ import annotations

import socket
import struct
from collections.abc import Mapping

from .errors import ProtocolError
from .tcpros import recv_length_prefixed

_U32 = struct.Struct("<I")


def encode_header(fields: Mapping[str, str]) -> bytes:
    """Encode ``fields`` into a header, total length prefix included."""
    body = bytearray()
    for key, value in fields.items():
        item = f"{key}={value}".encode()
        body += _U32.pack(len(item))
        body += item
    return _U32.pack(len(body)) + bytes(body)


def decode_header(body: bytes | bytearray | memoryview) -> dict[str, str]:
    """Decode header fields (without the total length prefix); raise ProtocolError if malformed."""
    fields: dict[str, str] = {}
    view = memoryview(body)
    pos = 0
    while pos < len(view):
        if pos + 4 > len(view):
            raise ProtocolError("connection header truncated inside a field length")
        (size,) = _U32.unpack_from(view, pos)
        pos += 4
        if pos + size > len(view):
            raise ProtocolError(f"connection header field of {size} bytes overruns the header")
        item = bytes(view[pos : pos + size])
        pos += size
        key, sep, value = item.partition(b"=")
        if not sep or not key:
            raise ProtocolError(f"connection header field without '=': {item[:40]!r}")
        try:
            fields[key.decode()] = value.decode()
        except UnicodeDecodeError as exc:
            raise ProtocolError("connection header field is not UTF-8") from exc
    return fields


def read_header(sock: socket.socket, max_bytes: int) -> dict[str, str]:
    """Read one header from ``sock``; its declared length must not exceed ``max_bytes``."""
    return decode_header(recv_length_prefixed(sock, max_bytes, what="connection header"))


def write_header(sock: socket.socket, fields: Mapping[str, str]) -> None:
    sock.sendall(encode_header(fields))


def error_header(reason: str) -> dict[str, str]:
    return {"error": reason}
