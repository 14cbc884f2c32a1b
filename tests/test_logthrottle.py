"""A flood of the same complaint is logged once per window, with a count of the rest."""

from __future__ import annotations

import logging

from egosim.logthrottle import LogThrottle


class Clock:
    def __init__(self) -> None:
        self.now = 0.0

    def __call__(self) -> float:
        return self.now


def test_a_flood_is_one_line_per_window_and_the_next_one_counts_the_rest(caplog) -> None:
    clock = Clock()
    throttle = LogThrottle(logging.getLogger("flood"), window_s=10.0, monotonic=clock)
    with caplog.at_level(logging.WARNING, logger="flood"):
        for k in range(313):
            clock.now = k * 0.01
            throttle.log(logging.WARNING, ("peer", "bad"), "bad frame %d", k)
        clock.now = 10.5
        throttle.log(logging.WARNING, ("peer", "bad"), "bad frame %d", 999)
    lines = [r.getMessage() for r in caplog.records]
    assert lines == ["bad frame 0", "bad frame 999 (312 more in the last 10 s)"]


def test_each_peer_and_reason_has_its_own_window(caplog) -> None:
    throttle = LogThrottle(logging.getLogger("keys"), window_s=10.0, monotonic=Clock())
    with caplog.at_level(logging.WARNING, logger="keys"):
        for key in [("a", "x"), ("a", "x"), ("b", "x"), ("a", "y")]:
            throttle.log(logging.WARNING, key, "%s", key)
    assert len(caplog.records) == 3
