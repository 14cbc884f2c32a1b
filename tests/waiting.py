"""Waiting in tests: every wait has a deadline and says what it waited for."""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import TypeVar

T = TypeVar("T")

DEFAULT_TIMEOUT_S = 30.0
#: Between two probes: a wait yields the core (the suite runs several tests at once on
#: two cores) and still sees the condition within a hundredth of a second.
POLL_S = 0.01


def until(probe: Callable[[], T | None], what: str, timeout_s: float = DEFAULT_TIMEOUT_S) -> T:
    """Call `probe` until it returns something other than None (or False); that value.
    Fails the test with `what` and the last value seen when `timeout_s` passes."""
    deadline = time.monotonic() + timeout_s
    last: T | None = None
    while time.monotonic() < deadline:
        last = probe()
        if last is not None and last is not False:
            return last
        time.sleep(POLL_S)
    raise AssertionError(f"timed out after {timeout_s:.0f} s waiting for {what}; last: {last!r}")
