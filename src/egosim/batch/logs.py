"""Bounded per-case logs: a process's output, its head and tail kept, the middle dropped;
the last lines of one, shown beside a verdict."""

from __future__ import annotations

import threading
from collections import deque
from collections.abc import Callable
from pathlib import Path
from typing import IO, TypedDict

DEFAULT_HEAD_BYTES = 256 * 1024
DEFAULT_TAIL_BYTES = 256 * 1024
TAIL_LINES = 20
"""Lines of a log shown beside a case's verdict: a Python traceback's end fits."""
MAX_LINE_CHARS = 300
"""A longer line is cut (a log line of megabytes must not flood a report)."""


class LogTail(TypedDict):
    """A result's `log_tail`: the log's file name in the case folder and its last lines
    (none: the log is empty or missing)."""

    file: str
    lines: list[str]


class BoundedFile:
    """A log file that keeps the first `head_bytes` written (as they come) and only the
    last `tail_bytes` after them (written on close, after a note of how much was
    dropped)."""

    def __init__(
        self,
        path: Path,
        head_bytes: int = DEFAULT_HEAD_BYTES,
        tail_bytes: int = DEFAULT_TAIL_BYTES,
    ) -> None:
        self.path = path
        self._file = path.open("wb")
        self._head = head_bytes
        self._tail_bytes = tail_bytes
        self._written = self._dropped = self._tail_size = 0
        self._tail: deque[bytes] = deque()

    def write(self, line: bytes) -> None:
        if self._written + len(line) <= self._head:
            self._file.write(line)
            self._file.flush()
            self._written += len(line)
            return
        self._tail.append(line)
        self._tail_size += len(line)
        while self._tail_size > self._tail_bytes:
            self._tail_size -= len(self._tail[0])
            self._dropped += len(self._tail.popleft())

    def close(self) -> None:
        if self._dropped:
            self._file.write(f"[... {self._dropped} bytes dropped ...]\n".encode())
        self._file.writelines(self._tail)
        self._file.close()


class BoundedLog:
    """Copies a stream to a BoundedFile line by line in a thread. `on_line` sees every
    line."""

    def __init__(
        self,
        stream: IO[bytes],
        path: Path,
        on_line: Callable[[str], None] | None = None,
        head_bytes: int = DEFAULT_HEAD_BYTES,
        tail_bytes: int = DEFAULT_TAIL_BYTES,
    ) -> None:
        self.path = path
        self._stream = stream
        self._on_line = on_line
        self._file = BoundedFile(path, head_bytes, tail_bytes)
        self._thread = threading.Thread(target=self._copy, name=f"log {path.name}", daemon=True)
        self._thread.start()

    def _copy(self) -> None:
        try:
            for line in self._stream:
                if self._on_line is not None:
                    self._on_line(line.decode("utf-8", "replace").rstrip("\n"))
                self._file.write(line)
        finally:
            self._file.close()
            self._stream.close()

    def join(self, timeout_s: float) -> None:
        self._thread.join(timeout_s)


def log_tail(folder: Path, name: str, count: int = TAIL_LINES) -> LogTail:
    """The last `count` non-blank lines of the log `name` in `folder`."""
    data, whole = _end_of(folder / name, count * (MAX_LINE_CHARS + 1))
    lines = data.decode("utf-8", "replace").splitlines()
    if not whole:
        lines = lines[1:]  # the read began inside a line
    kept = [line.rstrip() for line in lines if line.strip()][-count:]
    return {"file": name, "lines": [_cut(line) for line in kept]}


def _end_of(path: Path, size: int) -> tuple[bytes, bool]:
    """The last `size` bytes of a file (none if it cannot be read), and whether that is
    the whole file."""
    try:
        with path.open("rb") as file:
            start = max(file.seek(0, 2) - size, 0)
            file.seek(start)
            return file.read(), start == 0
    except OSError:
        return b"", True


def _cut(line: str) -> str:
    return line if len(line) <= MAX_LINE_CHARS else f"{line[:MAX_LINE_CHARS]} [...]"


def tail_report(tail: LogTail | None) -> list[str]:
    """A result's `log_tail` as lines for a person (console, JUnit, HTML): a heading, then
    the log's lines indented."""
    if tail is None:
        return []
    if not tail["lines"]:
        return [f"{tail['file']}: empty (the process wrote nothing)"]
    return [f"{tail['file']}, last lines:", *(f"  {line}" for line in tail["lines"])]
