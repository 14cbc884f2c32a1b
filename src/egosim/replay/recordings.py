"""Bags this process is recording right now, so nothing repairs or replays them mid-write."""

from __future__ import annotations

import threading
from pathlib import Path

_lock = threading.Lock()
_active: set[Path] = set()


def start_recording(path: Path) -> None:
    with _lock:
        _active.add(path.resolve())


def stop_recording(path: Path) -> None:
    with _lock:
        _active.discard(path.resolve())


def is_recording(path: Path) -> bool:
    with _lock:
        return path.resolve() in _active
