"""An HTTP request's header block, read as `http.client.parse_headers` reads it: the same
limits and errors, the same lines taken for headers, the same value for each name. That
function hands the block to the email package's parser, which costs an XML-RPC server a
quarter of its CPU per request; the few rules it applies to a header block are applied
here directly."""

from __future__ import annotations

import http.client
import io
import re
from typing import Protocol

MAX_LINE_BYTES = 65536
"""http.client's limit on a header line (its _MAXLINE)."""
MAX_LINES = 100
"""http.client's limit on the lines of a header block (its _MAXHEADERS)."""

# A line the email parser takes for part of the headers: a field name (printable ASCII
# but ':') and its colon, a folded continuation, or a Unix "From " line. The first other
# line ends the headers.
_HEADER_LINE = re.compile(r"From |[\041-\071\073-\176]*:|[\t ]")


class LineReader(Protocol):
    def readline(self, size: int = -1, /) -> bytes: ...


class Headers:
    """Header values by name, the name in any case; a repeated name has its first value,
    and a missing one is None, also by `headers[name]` (as email.message.Message)."""

    __slots__ = ("_values",)

    def __init__(self, values: dict[str, str]) -> None:
        self._values = values

    def get(self, name: str, default: str | None = None) -> str | None:
        return self._values.get(name.lower(), default)

    def __getitem__(self, name: str) -> str | None:
        return self._values.get(name.lower())


def read_headers(rfile: LineReader) -> Headers:
    """The headers from `rfile` up to the blank line that ends them (or the end of input).

    Raises http.client.LineTooLong for a line over MAX_LINE_BYTES and
    http.client.HTTPException for more than MAX_LINES lines, as parse_headers does.
    """
    lines = []
    while True:
        line = rfile.readline(MAX_LINE_BYTES + 1)
        if len(line) > MAX_LINE_BYTES:
            raise http.client.LineTooLong("header line")
        lines.append(line)
        if len(lines) > MAX_LINES:
            raise http.client.HTTPException(f"got more than {MAX_LINES} headers")
        if line in (b"\r\n", b"\n", b""):
            return parse_headers(b"".join(lines).decode("iso-8859-1"))


def parse_headers(block: str) -> Headers:
    """The headers of `block` as the email parser (compat32, as http.client uses it) finds
    them: lines end at CR, LF or CRLF; a name is what precedes the first colon, the value
    what follows it with leading blanks and the line's end stripped, folded lines appended
    as they are; a line without a name, or a "From " line, is no header."""
    values: dict[str, str] = {}
    name = ""
    value: list[str] = []
    for line in io.StringIO(block, newline="").readlines():
        if not _HEADER_LINE.match(line):
            break
        if line[0] in " \t":
            if name:
                value.append(line)
            continue
        if name:
            values.setdefault(name.lower(), "".join(value).rstrip("\r\n"))
        name, _, first = line.partition(":")
        if line.startswith("From "):
            name = ""
        value = [first.lstrip(" \t")]
    if name:
        values.setdefault(name.lower(), "".join(value).rstrip("\r\n"))
    return Headers(values)
