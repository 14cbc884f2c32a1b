"""A row's rate: evenly spaced from its first publication, averaging the rate on a loop
whose ticks do not divide the period, and no catch-up burst after a stall."""

from __future__ import annotations

from itertools import pairwise

import pytest

from egosim.bridge.rate_schedule import RateSchedule


def published(schedule: RateSchedule, ticks: list[float]) -> list[float]:
    return [t for t in ticks if schedule.take(t)]


def test_a_row_starting_on_an_odd_tick_keeps_whole_periods_from_its_first_message() -> None:
    # 50 Hz on a 100 Hz loop whose first tick is at 0.01 s: every gap is 20 ms, the first too.
    times = published(RateSchedule(50.0), [0.01 * k for k in range(1, 12)])
    assert [round(b - a, 9) for a, b in pairwise(times)] == [0.02] * 5


def test_a_rate_the_ticks_do_not_divide_averages_the_full_rate() -> None:
    # 30 Hz on a 100 Hz loop: gaps of 30 and 40 ms, 30 messages a second.
    times = published(RateSchedule(30.0), [0.01 * k for k in range(100)])
    assert len(times) == 30


def test_after_a_stall_the_grid_starts_afresh_without_a_burst() -> None:
    schedule = RateSchedule(10.0)
    assert published(schedule, [0.0, 0.05, 0.1]) == [0.0, 0.1]
    # The loop stalls for half a second: one message when it resumes, the next a period on.
    assert published(schedule, [0.6, 0.61, 0.65, 0.7]) == [0.6, 0.7]


@pytest.mark.parametrize("rate_hz", [None, 0.0])
def test_no_rate_means_every_tick(rate_hz: float | None) -> None:
    ticks = [0.0, 0.001, 0.002]
    assert published(RateSchedule(rate_hz), ticks) == ticks
