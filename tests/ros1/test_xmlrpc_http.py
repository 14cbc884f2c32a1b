"""The HTTP side of egosim's XML-RPC servers, byte for byte on a raw socket: what every
request gets back, answered as xmlrpc.server's handler answers it (rospy, roscpp and
rosmaster's clients rely on no more, and no less)."""

from __future__ import annotations

import email.utils
import gzip
import logging
import socket
import time
import xmlrpc.client

import pytest

from egosim.ros1 import Master
from egosim.ros1.rpc_handler import MAX_REQUEST_BYTES, RequestHandler
from tests.conftest import EVENT_TIMEOUT_S, free_port
from tests.ros1.helpers import drain, send_raw, uri_address, wait_until

SERVICE_API = "rosrpc://127.0.0.1:1234/"
LOOKUP = xmlrpc.client.dumps(("/client", "/svc"), "lookupService").encode()
# Forty lookups in one multicall: a reply well over the size that is sent gzipped.
MULTICALL = xmlrpc.client.dumps(
    ([{"methodName": "lookupService", "params": ["/client", "/svc"]}] * 40,), "system.multicall"
).encode()


@pytest.fixture
def master():
    master = Master(f"http://127.0.0.1:{free_port()}/").start()
    master.register_service("/provider", "/svc", SERVICE_API, "http://127.0.0.1:1/")
    try:
        yield master
    finally:
        master.shutdown()


def post(body: bytes = LOOKUP, *headers: str, version: str = "HTTP/1.1", path: str = "/") -> bytes:
    lines = [f"POST {path} {version}", "Host: 127.0.0.1", "Content-Type: text/xml", *headers]
    return ("\r\n".join(lines) + "\r\n\r\n").encode("latin-1") + body


def length(body: bytes = LOOKUP) -> str:
    return f"Content-Length: {len(body)}"


def split_reply(reply: bytes) -> tuple[str, dict[str, str], bytes]:
    """(status line, headers by lower-case name, body) of one HTTP reply."""
    head, separator, body = reply.partition(b"\r\n\r\n")
    assert separator, f"no end of headers in {reply[:200]!r}"
    status, *lines = head.decode("latin-1").split("\r\n")
    headers = {}
    for line in lines:
        name, _, value = line.partition(": ")
        headers[name.lower()] = value
    return status, headers, body


def looked_up(body: bytes) -> str:
    ((code, _message, api),) = xmlrpc.client.loads(body)[0]
    assert code == 1
    return str(api)


def test_a_lookup_gets_the_stdlib_handlers_http_1_0_reply(master):
    before = time.time()
    status, headers, body = split_reply(send_raw(uri_address(master.uri), post(LOOKUP, length())))
    assert status == "HTTP/1.0 200 OK"
    assert list(headers) == ["server", "date", "content-type", "content-length"]
    assert headers["server"].startswith("BaseHTTP/")
    assert headers["content-type"] == "text/xml"
    assert int(headers["content-length"]) == len(body)
    date = email.utils.parsedate_to_datetime(headers["date"]).timestamp()
    assert int(before) <= date <= time.time()
    assert looked_up(body) == SERVICE_API


@pytest.mark.parametrize("path", ["/", "/RPC2", "//several//slashes", "*"])
def test_any_path_is_answered(master, path):
    reply = send_raw(uri_address(master.uri), post(LOOKUP, length(), path=path))
    assert looked_up(split_reply(reply)[2]) == SERVICE_API


@pytest.mark.parametrize(
    "headers",
    [
        ("content-LENGTH: %d",),
        ("CONTENT-LENGTH:   %d  ",),
        ("Content-Length: %d", "Content-Length: 3"),  # the first of two counts
        ("Content-Length:", " %d"),  # folded onto a second line
    ],
    ids=["odd case", "blanks around", "repeated", "folded"],
)
def test_content_length_is_read_however_it_is_written(master, headers):
    lines = [line.replace("%d", str(len(LOOKUP))) for line in headers]
    reply = send_raw(uri_address(master.uri), post(LOOKUP, *lines))
    assert looked_up(split_reply(reply)[2]) == SERVICE_API


@pytest.mark.parametrize("encoding", ["gzip", "GZIP"])
def test_a_gzipped_request_is_answered(master, encoding):
    body = gzip.compress(LOOKUP)
    reply = send_raw(
        uri_address(master.uri), post(body, length(body), f"content-encoding: {encoding}")
    )
    assert looked_up(split_reply(reply)[2]) == SERVICE_API


@pytest.mark.parametrize(
    ("encoding", "body", "status"),
    [
        ("gzip", b"not gzip at all", "HTTP/1.0 400 error decoding gzip content"),
        ("deflate", LOOKUP, "HTTP/1.0 501 encoding 'deflate' not supported"),
    ],
)
def test_an_undecodable_request_is_refused(master, caplog, encoding, body, status):
    caplog.set_level(logging.WARNING, logger="egosim.ros1")
    reply = send_raw(
        uri_address(master.uri), post(body, length(body), f"Content-Encoding: {encoding}")
    )
    assert split_reply(reply)[0] == status
    assert split_reply(reply)[2] == b""
    logged = any('"POST / HTTP/1.1" 501' in r.getMessage() for r in caplog.records)
    assert logged == status.startswith("HTTP/1.0 501")


@pytest.mark.parametrize(
    ("accept", "gzipped"),
    [("Accept-Encoding: gzip", True), ("Accept-Encoding: gzip;q=0", False), (None, False)],
)
def test_a_long_reply_is_gzipped_for_a_peer_that_accepts_it(master, accept, gzipped):
    headers = [length(MULTICALL)] + ([accept] if accept else [])
    _, reply_headers, body = split_reply(
        send_raw(uri_address(master.uri), post(MULTICALL, *headers))
    )
    assert int(reply_headers["content-length"]) == len(body)
    assert (reply_headers.get("content-encoding") == "gzip") == gzipped
    results = xmlrpc.client.loads(gzip.decompress(body) if gzipped else body)[0][0]
    assert [api for [(_code, _message, api)] in results] == [SERVICE_API] * 40


@pytest.mark.parametrize(
    ("declared", "status"),
    [
        ("abc", "400"),
        ("-5", "400"),
        (str(MAX_REQUEST_BYTES + 1), "413"),
    ],
)
def test_a_bad_or_oversized_content_length_is_refused(master, declared, status):
    reply = send_raw(uri_address(master.uri), post(b"", f"Content-Length: {declared}"))
    assert split_reply(reply)[0] == f"HTTP/1.0 {status} bad or oversized Content-Length"


def test_a_request_without_content_length_gets_a_500_and_is_logged(master, caplog):
    caplog.set_level(logging.WARNING, logger="egosim.ros1")
    status, headers, body = split_reply(send_raw(uri_address(master.uri), post(LOOKUP)))
    assert status == "HTTP/1.0 500 Internal Server Error"
    assert headers["content-length"] == "0" and body == b""
    assert any('"POST / HTTP/1.1" 500' in r.getMessage() for r in caplog.records)


@pytest.mark.parametrize(
    ("request_line", "status"),
    [
        ("POST / extra HTTP/1.0", "HTTP/1.0 400 Bad request syntax ('POST / extra HTTP/1.0')"),
        ("GET / HTTP/1.0", "HTTP/1.0 501 Unsupported method ('GET')"),
        ("post / HTTP/1.0", "HTTP/1.0 501 Unsupported method ('post')"),
    ],
)
def test_a_bad_request_line_gets_the_stdlib_error_page(master, request_line, status):
    reply = send_raw(
        uri_address(master.uri), f"{request_line}\r\n{length()}\r\n\r\n".encode() + LOOKUP
    )
    got_status, headers, body = split_reply(reply)
    assert got_status == status
    assert headers["connection"] == "close"
    assert headers["content-type"] == "text/html;charset=utf-8"
    assert int(headers["content-length"]) == len(body)
    assert b"<title>Error response</title>" in body


@pytest.mark.parametrize(
    ("request_line", "error"),
    [
        ("POST / HTTP/1.x", "Error code: 400</p>\n        <p>Message: Bad request version"),
        ("POST / FTP/1.0", "Error code: 400</p>\n        <p>Message: Bad request version"),
        ("POST / HTTP/2.0", "Error code: 505</p>\n        <p>Message: Invalid HTTP version"),
        ("POST", "Error code: 400</p>\n        <p>Message: Bad request syntax ('POST')"),
        ("POST /", "Error code: 400</p>\n        <p>Message: Bad HTTP/0.9 request type"),
        ("GET /", "Error code: 501</p>\n        <p>Message: Unsupported method ('GET')"),
    ],
)
def test_a_request_line_without_a_version_understood_gets_only_the_error_page(
    master, request_line, error
):
    # Answered as to an HTTP/0.9 request: no status line, no headers.
    reply = send_raw(uri_address(master.uri), f"{request_line}\r\n\r\n".encode())
    assert reply.startswith(b"<!DOCTYPE HTML>")
    assert error.encode() in reply


@pytest.mark.parametrize(
    ("data", "status"),
    [
        (post(LOOKUP, length(), *(f"X-{k}: {k}" for k in range(100))), "431 Too many headers"),
        (post(LOOKUP, length(), "X-Long: " + "a" * 65536), "431 Line too long"),
        (b"POST /" + b"a" * 65536 + b" HTTP/1.0\r\n\r\n", "414 Request-URI Too Long"),
    ],
    ids=["too many headers", "a header line too long", "a request line too long"],
)
def test_a_request_over_the_header_limits_is_refused(master, data, status):
    assert split_reply(send_raw(uri_address(master.uri), data))[0] == f"HTTP/1.0 {status}"


def test_a_keep_alive_request_is_answered_once_and_the_connection_closed(master):
    two = post(LOOKUP, length(), "Connection: keep-alive") + post(LOOKUP, length())
    reply = send_raw(uri_address(master.uri), two)
    assert reply.count(b"HTTP/1.0 200 OK") == 1
    assert looked_up(split_reply(reply)[2]) == SERVICE_API


def test_expect_100_continue_gets_no_interim_reply(master):
    with socket.create_connection(uri_address(master.uri), timeout=EVENT_TIMEOUT_S) as sock:
        sock.sendall(post(b"", length(), "Expect: 100-continue"))
        sock.sendall(LOOKUP)  # the body, sent without waiting for a 100 Continue
        reply = drain(sock)
    assert reply.startswith(b"HTTP/1.0 200 OK\r\n")
    assert looked_up(split_reply(reply)[2]) == SERVICE_API


def test_a_peer_that_never_finishes_is_dropped_after_the_timeout(master, monkeypatch, caplog):
    caplog.set_level(logging.WARNING, logger="egosim.ros1")
    monkeypatch.setattr(RequestHandler, "timeout", 0.2)
    address = uri_address(master.uri)
    with socket.create_connection(address, timeout=EVENT_TIMEOUT_S) as sock:
        sock.sendall(b"POST / HTTP/1.1\r\nContent-Len")
        assert sock.recv(1) == b""  # closed with nothing said
    wait_until(lambda: any("Request timed out" in r.getMessage() for r in caplog.records))
    with socket.create_connection(address, timeout=EVENT_TIMEOUT_S) as sock:
        sock.sendall(post(LOOKUP[:20], length()))  # the body stops short
        status = sock.recv(65536).split(b"\r\n", 1)[0]
    assert status == b"HTTP/1.0 500 Internal Server Error"
    assert xmlrpc.client.ServerProxy(master.uri).lookupService("/client", "/svc")[2] == SERVICE_API


def test_a_body_cut_short_by_the_peer_gets_a_fault(master):
    reply = send_raw(uri_address(master.uri), post(LOOKUP[:-10], length()))
    with pytest.raises(xmlrpc.client.Fault, match="request is not XML-RPC"):
        xmlrpc.client.loads(split_reply(reply)[2])
