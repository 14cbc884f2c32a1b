"""The HTTP side of the XML-RPC server: a connection's one request read and answered as
xmlrpc.server's SimpleXMLRPCRequestHandler reads and answers it (the same replies, the
same errors, the same log lines), at a fraction of its CPU. Headers are read by
http_headers instead of the email package, and a reply goes out whole in one send.

rospy's ServiceProxy asks the master for the service's address at every call, on a new
connection: a batch case makes hundreds of these requests, each paying for the HTTP
exchange far more than for the lookup."""

from __future__ import annotations

import email.utils
import http.client
import logging
import time
import xmlrpc.client
from http import HTTPStatus
from typing import Protocol
from xmlrpc.server import SimpleXMLRPCRequestHandler

from .http_headers import Headers, read_headers

log = logging.getLogger(__name__)

MAX_REQUEST_BYTES = 64 * 1024 * 1024
"""Largest XML-RPC request body accepted (the largest ROS calls carry parameter trees)."""

GZIP_REPLIES_OVER_BYTES = 1400
"""A longer reply goes out gzipped to a peer that accepts gzip (SimpleXMLRPCRequestHandler's
encode_threshold: a common MTU)."""


class AnsweringServer(Protocol):
    """The server a handler serves (rpc.XmlRpcServer): what it replies to a request."""

    def answer(self, request: bytes, peer: object) -> bytes: ...


class RequestHandler(SimpleXMLRPCRequestHandler):
    server: AnsweringServer  # type: ignore[assignment]  # an XmlRpcServer, which is one
    headers: Headers  # type: ignore[assignment]  # read by read_headers, not the email parser
    raw_requestline: bytes  # read by handle_one_request

    # One request a connection, answered HTTP/1.0 and closed, whatever the request's
    # version or its Connection header; an Expect: 100-continue gets no interim reply.
    # rospy, roscpp and rosmaster's clients work with this, the stdlib handler's default.
    protocol_version = "HTTP/1.0"
    # Any path is accepted: roscpp posts to "/RPC2", rospy to "/".
    rpc_paths = ()
    # A peer that opens a connection and never finishes its request is dropped.
    timeout = 10
    # Nothing is buffered for writing: a reply is written whole.
    wbufsize = 0

    def parse_request(self) -> bool:
        """BaseHTTPRequestHandler.parse_request's checks of the request line, its replies
        to a bad one, then the headers from read_headers."""
        self.command = ""  # none yet (send_error reads it)
        self.request_version = self.default_request_version
        self.close_connection = True
        self.requestline = str(self.raw_requestline, "iso-8859-1").rstrip("\r\n")
        words = self.requestline.split()
        if not words:
            return False
        if len(words) >= 3:
            version = words[-1]
            number = _version_number(version)
            if number is None:
                self.send_error(HTTPStatus.BAD_REQUEST, f"Bad request version ({version!r})")
                return False
            if number >= (2, 0):
                self.send_error(
                    HTTPStatus.HTTP_VERSION_NOT_SUPPORTED,
                    f"Invalid HTTP version ({version.split('/', 1)[1]})",
                )
                return False
            self.request_version = version
        if not 2 <= len(words) <= 3:
            self.send_error(HTTPStatus.BAD_REQUEST, f"Bad request syntax ({self.requestline!r})")
            return False
        self.command, self.path = words[:2]
        if len(words) == 2 and self.command != "GET":
            self.send_error(HTTPStatus.BAD_REQUEST, f"Bad HTTP/0.9 request type ({self.command!r})")
            return False
        if self.path.startswith("//"):
            self.path = "/" + self.path.lstrip("/")
        try:
            self.headers = read_headers(self.rfile)
        except http.client.LineTooLong as exc:
            self.send_error(HTTPStatus.REQUEST_HEADER_FIELDS_TOO_LARGE, "Line too long", str(exc))
            return False
        except http.client.HTTPException as exc:
            self.send_error(
                HTTPStatus.REQUEST_HEADER_FIELDS_TOO_LARGE, "Too many headers", str(exc)
            )
            return False
        return True

    def do_POST(self) -> None:  # noqa: N802 (name given by BaseHTTPRequestHandler)
        declared = self.headers["content-length"]
        if declared is None:
            # A body without a length (chunked, or up to the end of input) cannot be read:
            # refused with the stdlib handler's 500, and so logged.
            self._send_failure()
            return
        try:
            length = int(declared)
        except ValueError:
            length = -1
        if not 0 <= length <= MAX_REQUEST_BYTES:
            self.send_error(413 if length > 0 else 400, "bad or oversized Content-Length")
            return
        try:
            request = self.decode_request_content(self.rfile.read(length))
            if request is None:  # its error reply went out
                return
            reply = self.server.answer(request, self.client_address)
        except Exception:  # the peer went quiet mid-body, or the dispatcher failed
            self._send_failure()
            return
        self._send_reply(reply)

    def _send_reply(self, reply: bytes) -> None:
        encoding = ""
        if len(reply) > GZIP_REPLIES_OVER_BYTES and self.accept_encodings().get("gzip", 0):
            reply = xmlrpc.client.gzip_encode(reply)
            encoding = "Content-Encoding: gzip\r\n"
        head = (
            f"{self.protocol_version} 200 OK\r\nServer: {self.version_string()}\r\n"
            f"Date: {self.date_time_string()}\r\nContent-type: text/xml\r\n{encoding}"
            f"Content-length: {len(reply)}\r\n\r\n"
        )
        self.wfile.write(head.encode("latin-1") + reply)

    def _send_failure(self) -> None:
        self.send_response(500)
        self.send_header("Content-length", "0")
        self.end_headers()

    def date_time_string(self, timestamp: float | None = None) -> str:
        if timestamp is not None:
            return super().date_time_string(timestamp)
        return _date_header.now()

    def log_message(self, format: str, *args: object) -> None:
        log.warning("XML-RPC peer %s: %s", self.address_string(), format % args)

    def log_request(self, code: int | str = "-", size: int | str = "-") -> None:
        # Answered requests stay quiet; a request the server failed on (such as a chunked
        # body, which it cannot read) is logged.
        if str(code).isdigit() and int(code) >= 500:
            self.log_message('"%s" %s', self.requestline, code)


def _version_number(version: str) -> tuple[int, int] | None:
    """(major, minor) of "HTTP/major.minor", None if `version` is no such thing (the numbers
    as BaseHTTPRequestHandler takes them: decimal digits, at most 10 of each)."""
    if not version.startswith("HTTP/"):
        return None
    numbers = version[5:].split(".")
    if len(numbers) != 2 or not all(n.isascii() and n.isdigit() and len(n) <= 10 for n in numbers):
        return None
    return int(numbers[0]), int(numbers[1])


class _DateHeader:
    """The Date header's value now, formatted once a second (as BaseHTTPRequestHandler
    formats it: email.utils.formatdate in GMT, to the second)."""

    def __init__(self) -> None:
        self._formatted = (-1, "")

    def now(self) -> str:
        second = int(time.time())
        formatted = self._formatted  # one read: a (second, text) pair another thread replaces
        if formatted[0] != second:
            formatted = self._formatted = (second, email.utils.formatdate(second, usegmt=True))
        return formatted[1]


_date_header = _DateHeader()
