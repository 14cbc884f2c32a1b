"""Bounded per-case logs: a process's output, its head and tail kept, the middle dropped."""

from __future__ import annotations

import threading
from collections import deque
from collections.abc import Callable
from pathlib import Path
from typing import IO

DEFAULT_HEAD_BYTES = 256 * 1024
DEFAULT_TAIL_BYTES = 256 * 1024


class BoundedLog:
    """Copies a stream to a file line by line in a thread: the first `head_bytes` as they
    come, then only the last `tail_bytes` (written at the end, after a note of how much
    was dropped). `on_line` sees every line."""

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
        self._head = head_bytes
        self._tail_bytes = tail_bytes
        self._thread = threading.Thread(target=self._copy, name=f"log {path.name}", daemon=True)
        self._thread.start()

    def _copy(self) -> None:
        written = dropped = tail_size = 0
        tail: deque[bytes] = deque()
        with self.path.open("wb") as file:
            for line in self._stream:
                if self._on_line is not None:
                    self._on_line(line.decode("utf-8", "replace").rstrip("\n"))
                if written + len(line) <= self._head:
                    file.write(line)
                    file.flush()
                    written += len(line)
                    continue
                tail.append(line)
                tail_size += len(line)
                while tail_size > self._tail_bytes:
                    tail_size -= len(tail[0])
                    dropped += len(tail.popleft())
            if dropped:
                file.write(f"[... {dropped} bytes dropped ...]\n".encode())
            file.writelines(tail)
        self._stream.close()

    def join(self, timeout_s: float) -> None:
        self._thread.join(timeout_s)


def tail_text(path: Path, size: int = 2000) -> str:
    """The end of a log file, for a failure's reason."""
    try:
        data = path.read_bytes()
    except OSError:
        return ""
    return data[-size:].decode("utf-8", "replace").strip()
