"""Rate-limited logging: a stream of the same complaint is logged once per window, with
a count of the ones held back.

A peer that sends 500 malformed requests a second must not bury every other line of
the log; it still must not go unnoticed. The first occurrence of a key is logged at
once; later ones within `window_s` are counted, and the next one logged after the
window says how many were held back ("... (312 more in the last 10 s)").
"""

from __future__ import annotations

import logging
import threading
import time
import weakref
from collections.abc import Callable, Hashable

DEFAULT_WINDOW_S = 10.0
#: Keys remembered at most (one per peer and reason); the oldest are forgotten first.
MAX_KEYS = 1024

_throttles: weakref.WeakSet[LogThrottle] = weakref.WeakSet()


def forget_every_window() -> None:
    """Start every throttle of the process afresh, as in a new process (a process that
    runs one simulation after another does this between them)."""
    for throttle in list(_throttles):
        throttle.forget()


class LogThrottle:
    def __init__(
        self,
        logger: logging.Logger,
        window_s: float = DEFAULT_WINDOW_S,
        monotonic: Callable[[], float] = time.monotonic,
    ) -> None:
        self._logger = logger
        self._window_s = window_s
        self._monotonic = monotonic
        self._lock = threading.Lock()
        # key -> (start of its window, occurrences held back in it)
        self._windows: dict[Hashable, tuple[float, int]] = {}
        _throttles.add(self)

    def forget(self) -> None:
        """Forget every window (and what was held back in it)."""
        with self._lock:
            self._windows.clear()

    def log(
        self,
        level: int,
        key: Hashable,
        message: str,
        *args: object,
        exc_info: bool = False,
    ) -> bool:
        """Log `message % args` unless `key` was logged less than a window ago (then
        count it); True if it was logged."""
        now = self._monotonic()
        with self._lock:
            start, held = self._windows.pop(key, (None, 0))
            if start is not None and now - start < self._window_s:
                self._windows[key] = (start, held + 1)
                return False
            self._windows[key] = (now, 0)
            while len(self._windows) > MAX_KEYS:
                del self._windows[next(iter(self._windows))]
        if held:
            message += " (%d more in the last %.0f s)"
            args = (*args, held, now - start if start is not None else 0.0)
        self._logger.log(level, message, *args, exc_info=exc_info, stacklevel=2)
        return True
