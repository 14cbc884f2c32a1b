"""Request headers read as http.client.parse_headers reads them (the reading every stdlib
HTTP server does): the same value for each name, the same lines taken for headers, the
same limits and errors."""

from __future__ import annotations

import http.client
import io

import pytest

from egosim.ros1.http_headers import MAX_LINE_BYTES, MAX_LINES, read_headers

NAMES = (
    "Content-Length",
    "Content-Encoding",
    "Accept-Encoding",
    "Connection",
    "Expect",
    "Host",
    "X-Name",
    "From",
    "From x",
)

BLOCKS = {
    "xmlrpc.client's": b"Host: 127.0.0.1:11311\r\nAccept-Encoding: gzip\r\n"
    b"Content-Type: text/xml\r\nUser-Agent: Python-xmlrpc/3.11\r\nContent-Length: 213\r\n\r\n",
    "roscpp's": b"User-Agent: XMLRPC++ 0.7\r\nHost: 127.0.0.1:11311\r\n"
    b"Content-Type: text/xml\r\nContent-length: 227\r\n\r\n",
    "names in odd case": b"content-LENGTH: 5\r\nCONTENT-encoding: gzip\r\n\r\n",
    "a repeated name": b"Content-Length: 5\r\ncontent-length: 7\r\n\r\n",
    "blanks around a value": b"Content-Length: \t 5 \t\r\nX-Name:\r\n\r\n",
    "a folded value": b"Content-Length:\r\n 5\r\nX-Name: a\r\n\tb\r\n  c\r\n\r\n",
    "bare line feeds": b"Content-Length: 5\nX-Name: a\n\n",
    "a bare carriage return splits a line": b"X-Name: a\rContent-Length: 5\r\n\r\n",
    "a name with a blank ends the headers": b"X-Name: a\r\nContent Length: 5\r\nExpect: x\r\n\r\n",
    "a line without a colon ends the headers": b"X-Name: a\r\nnonsense\r\nHost: h\r\n\r\n",
    "a name beyond ASCII ends the headers": b"X-Caf\xe9: 1\r\nHost: h\r\n\r\n",
    "a value beyond ASCII": b"X-Name: caf\xe9\r\n\r\n",
    "a form feed or NEL breaks no line": b"X-Name: a\x0cb\x85c\x1cd\r\nHost: h\r\n\r\n",
    "an empty name": b": v\r\n folded\r\nHost: h\r\n\r\n",
    "a first line folded": b"  Content-Length: 5\r\nHost: h\r\n\r\n",
    "From lines": b"From someone\r\nHost: h\r\nFrom x: y\r\n cont\r\nFrom: me\r\n\r\n",
    "no blank line before the end": b"Host: h\r\nX-Name: a\r\n",
    "nothing": b"",
    "only the blank line": b"\r\n",
}


@pytest.mark.parametrize("block", BLOCKS.values(), ids=BLOCKS.keys())
def test_each_name_has_the_value_the_stdlib_reads(block: bytes) -> None:
    ours = read_headers(io.BytesIO(block + b"<methodCall/>"))
    stdlib = http.client.parse_headers(io.BytesIO(block + b"<methodCall/>"))
    for name in NAMES:
        for spelling in (name, name.lower(), name.upper()):
            assert ours.get(spelling) == stdlib.get(spelling), spelling
            assert ours[spelling] == stdlib[spelling], spelling
            assert ours.get(spelling, "missing") == stdlib.get(spelling, "missing"), spelling


def test_reading_stops_at_the_blank_line() -> None:
    stream = io.BytesIO(b"Content-Length: 4\r\n\r\nbody")
    read_headers(stream)
    assert stream.read() == b"body"


@pytest.mark.parametrize(
    ("block", "error"),
    [
        (b"X-Long: " + b"a" * MAX_LINE_BYTES + b"\r\n\r\n", "header line"),
        (b"".join(b"X-%d: %d\r\n" % (k, k) for k in range(MAX_LINES)) + b"\r\n", "100 headers"),
    ],
    ids=["a line too long", "too many lines"],
)
def test_a_block_over_the_limits_raises_what_the_stdlib_raises(block: bytes, error: str) -> None:
    with pytest.raises(http.client.HTTPException) as ours:
        read_headers(io.BytesIO(block))
    with pytest.raises(http.client.HTTPException) as stdlib:
        http.client.parse_headers(io.BytesIO(block))
    assert type(ours.value) is type(stdlib.value)
    assert str(ours.value) == str(stdlib.value)
    assert error in str(ours.value)


def test_a_block_at_the_limits_is_read() -> None:
    longest = b"X-Long: " + b"a" * (MAX_LINE_BYTES - 10) + b"\r\n"
    lines = [longest] + [b"X-%d: %d\r\n" % (k, k) for k in range(MAX_LINES - 2)]
    headers = read_headers(io.BytesIO(b"".join(lines) + b"\r\n"))
    assert headers["x-long"] == "a" * (MAX_LINE_BYTES - 10)
    assert headers["x-97"] == "97"
