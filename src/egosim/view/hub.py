"""The hand-over of frames from the simulation loop to the web server.

The loop never waits on the server: `offer` swaps one reference under a lock held for
a few instructions and pokes the server's event loop. The server keeps only the
newest frame, so memory stays bounded however slow the browsers are.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable
from typing import Any

from .snapshot import encode

#: Frames per second the loop offers at most (and so the browsers receive at most).
MAX_FRAME_RATE_HZ = 30.0


class FrameHub:
    """The newest captured frame, its JSON made once for every client."""

    def __init__(
        self,
        max_rate_hz: float = MAX_FRAME_RATE_HZ,
        monotonic: Callable[[], float] = time.monotonic,
    ) -> None:
        self._period = 1.0 / max_rate_hz
        self._monotonic = monotonic
        self._lock = threading.Lock()
        self._frame: dict[str, Any] | None = None
        self._sequence = 0
        self._encoded: tuple[int, str] | None = None
        self._next_due = -float("inf")
        self.clients = 0
        """Browsers connected (set by the server); no client, no frame is taken."""
        self.lidar_wanted = False
        """Some browser shows the LiDAR layer (set by the server)."""
        self.notify: Callable[[], None] = lambda: None
        """Called after each offer, from the loop thread (set by the server)."""

    def due(self) -> bool:
        """A frame should be taken now: someone watches and the rate allows it."""
        return self.clients > 0 and self._monotonic() >= self._next_due

    def offer(self, frame: dict[str, Any]) -> None:
        """Publish a captured frame (loop thread); replaces any not yet sent."""
        # Due times keep to the rate's grid, so a loop whose ticks do not divide the
        # period still averages the full rate; after a stall the grid starts afresh.
        now = self._monotonic()
        on_grid = now - self._next_due < self._period
        self._next_due = (self._next_due if on_grid else now) + self._period
        with self._lock:
            self._frame = frame
            self._sequence += 1
        self.notify()

    @property
    def sequence(self) -> int:
        """Number of frames offered so far; a client that has sent this many is up to date."""
        return self._sequence

    def latest(self) -> tuple[int, str] | None:
        """(sequence, JSON) of the newest frame, encoded once (server thread)."""
        with self._lock:
            frame, sequence = self._frame, self._sequence
        if frame is None:
            return None
        encoded = self._encoded
        if encoded is None or encoded[0] != sequence:
            encoded = self._encoded = (sequence, encode(frame))
        return encoded
