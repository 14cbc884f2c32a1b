"""A case's log keeps the start and the end of a process's output, bounded."""

from __future__ import annotations

import io
from pathlib import Path

from egosim.batch.logs import BoundedLog, log_tail


def test_a_long_output_keeps_its_head_and_tail_and_says_what_it_dropped(tmp_path: Path) -> None:
    lines = [f"line {k:05d}\n".encode() for k in range(10_000)]  # 11 bytes each
    seen: list[str] = []
    log = BoundedLog(io.BytesIO(b"".join(lines)), tmp_path / "out.log", seen.append, 1100, 1100)
    log.join(10.0)
    text = (tmp_path / "out.log").read_text()
    kept = text.splitlines()
    assert kept[:100] == [f"line {k:05d}" for k in range(100)]
    assert kept[100] == f"[... {(10_000 - 200) * 11} bytes dropped ...]"
    assert kept[101:] == [f"line {k:05d}" for k in range(9_900, 10_000)]
    assert len(seen) == 10_000  # every line still reaches the watcher
    assert log_tail(tmp_path, "out.log", 1) == {"file": "out.log", "lines": ["line 09999"]}


def test_a_short_output_is_kept_whole(tmp_path: Path) -> None:
    log = BoundedLog(io.BytesIO(b"one\ntwo\n"), tmp_path / "out.log")
    log.join(10.0)
    assert (tmp_path / "out.log").read_text() == "one\ntwo\n"
