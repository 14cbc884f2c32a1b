"""The hand-over of frames from the simulation loop to the web server.

The loop never waits on the server: `offer` swaps one reference under a lock held for
a few instructions and pokes the server's event loop. The server keeps only the
newest frame, so memory stays bounded however slow the browsers are.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable

from ..bridge.rate_schedule import RateSchedule
from .messages import CapturedFrame
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
        self._rate = RateSchedule(max_rate_hz)
        self._monotonic = monotonic
        self._lock = threading.Lock()
        self._frame: CapturedFrame | None = None
        self._sequence = 0
        self._encoded: tuple[int, str] | None = None
        self.clients = 0
        """Browsers connected (set by the server); no client, no frame is taken."""
        self.lidar_wanted = False
        """Some browser shows the LiDAR layer (set by the server)."""
        self.notify: Callable[[], None] = lambda: None
        """Called after each offer, from the loop thread (set by the server)."""

    def due(self) -> bool:
        """A frame should be taken now: someone watches and the rate allows it."""
        return self.clients > 0 and self._rate.is_due(self._monotonic())

    def offer(self, frame: CapturedFrame) -> None:
        """Publish a captured frame (loop thread); replaces any not yet sent."""
        self._rate.advance(self._monotonic())
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
