"""Connection header encoding (ROS wiki: ROS/Connection Header)."""

from __future__ import annotations

import struct

import pytest

from egosim.ros1 import ProtocolError
from egosim.ros1.connection_header import decode_header, encode_header


def test_example_from_the_spec_round_trips():
    fields = {"callerid": "/talker", "md5sum": "992ce8a1687cec8c8bd883ec73ca41d1", "topic": "/c"}
    data = encode_header(fields)
    (total,) = struct.unpack_from("<I", data)
    assert total == len(data) - 4
    assert data[4:8] == struct.pack("<I", len(b"callerid=/talker"))
    assert decode_header(data[4:]) == fields


def test_values_may_contain_equals_signs_and_newlines():
    fields = {"message_definition": "a=b\nstring data\n", "empty": ""}
    assert decode_header(encode_header(fields)[4:]) == fields


@pytest.mark.parametrize(
    "body",
    [
        b"\x05\x00",  # truncated field length
        struct.pack("<I", 50) + b"short=1",  # field overruns the header
        struct.pack("<I", 7) + b"noequal",  # no '='
        struct.pack("<I", 2) + b"=x",  # empty key
        struct.pack("<I", 3) + b"a=\xff",  # not UTF-8
    ],
)
def test_malformed_headers_raise_protocol_error(body):
    with pytest.raises(ProtocolError):
        decode_header(body)
