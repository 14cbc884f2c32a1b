"""The loop's hand-over to the server: at most 30 frames/s, only while watched, newest only."""

from __future__ import annotations

import json

from egosim.view.hub import FrameHub


class Clock:
    def __init__(self) -> None:
        self.now = 0.0

    def __call__(self) -> float:
        return self.now


def test_no_frame_is_due_without_a_browser() -> None:
    hub = FrameHub(monotonic=Clock())
    assert not hub.due()
    hub.clients = 1
    assert hub.due()


def test_frames_are_due_at_most_at_the_rate() -> None:
    clock = Clock()
    hub = FrameHub(max_rate_hz=30.0, monotonic=clock)
    hub.clients = 1
    offered = 0
    for _ in range(1000):  # one simulated second of 1 ms ticks
        clock.now += 0.001
        if hub.due():
            hub.offer({"n": offered})
            offered += 1
    assert 28 <= offered <= 30


def test_only_the_newest_frame_is_kept_and_it_is_encoded_once() -> None:
    hub = FrameHub(monotonic=Clock())
    woken = []
    hub.notify = lambda: woken.append(1)
    assert hub.latest() is None
    hub.offer({"n": 1})
    hub.offer({"n": 2})
    sequence, text = hub.latest()
    assert (sequence, json.loads(text)) == (2, {"n": 2})
    assert hub.latest()[1] is text
    assert len(woken) == 2
