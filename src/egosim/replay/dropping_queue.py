"""A bounded FIFO between a producer that must never wait and one consumer thread."""

from __future__ import annotations

import threading
from collections import deque
from typing import Generic, TypeVar

Item = TypeVar("Item")


class DroppingQueue(Generic[Item]):
    """Refuses (and counts) items instead of blocking the producer when full.

    Bounded both in items and in payload bytes, so a burst of large messages
    (point clouds) cannot exhaust memory while the consumer is stuck on a disk.
    """

    def __init__(self, max_items: int, max_bytes: int) -> None:
        if max_items < 1 or max_bytes < 1:
            raise ValueError("queue limits must be positive")
        self.max_items = max_items
        self.max_bytes = max_bytes
        self._items: deque[tuple[Item, int]] = deque()
        self._bytes = 0
        self._closed = False
        self._dropped = 0
        self._ready = threading.Condition(threading.Lock())

    @property
    def dropped(self) -> int:
        """Items refused so far because the queue was full."""
        return self._dropped

    def offer(self, item: Item, size: int) -> bool:
        """Append `item` (of `size` payload bytes) unless full or closed; never waits."""
        with self._ready:
            if (
                self._closed
                or len(self._items) >= self.max_items
                or self._bytes + size > self.max_bytes
            ):
                self._dropped += 1
                return False
            self._items.append((item, size))
            self._bytes += size
            self._ready.notify()
            return True

    def take_all(self, timeout: float) -> tuple[list[Item], bool]:
        """Everything queued (waiting up to `timeout` s for the first item) and whether closed."""
        with self._ready:
            if not self._items and not self._closed:
                self._ready.wait(timeout)
            items = [item for item, _ in self._items]
            self._items.clear()
            self._bytes = 0
            return items, self._closed

    def close(self) -> None:
        """Refuse further items and wake the consumer so it can finish."""
        with self._ready:
            self._closed = True
            self._ready.notify_all()
