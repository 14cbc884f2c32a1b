"""How a run's stop requests are seen (app/signals.py): by a watcher thread, whatever the
main thread is doing; a second signal or an overrun deadline forces the exit, after the
closers (the bag) ran. The exit itself is stood in for here (the real one: tests/e2e/
test_stops.py)."""

from __future__ import annotations

import os
import signal
import threading
import time
from collections.abc import Iterator

import pytest

from egosim.app.exit_codes import EXIT_STOP_FORCED
from egosim.app.signals import FORCED_CLOSE_S, StopControl, stop_on_signals
from tests.waiting import until

WAIT_S = 10.0


class Exits:
    """Stands in for os._exit: records the status, and wakes whoever waits for it."""

    def __init__(self) -> None:
        self.statuses: list[int] = []
        self.happened = threading.Event()

    def __call__(self, status: int) -> None:
        self.statuses.append(status)
        self.happened.set()


@pytest.fixture
def exits() -> Exits:
    return Exits()


@pytest.fixture
def control(exits: Exits) -> Iterator[StopControl]:
    with stop_on_signals(threading.Event(), deadline_s=None, exit_process=exits) as control:
        yield control


@pytest.mark.parametrize("number", [signal.SIGINT, signal.SIGTERM, signal.SIGHUP])
def test_a_signal_asks_for_a_clean_stop(
    control: StopControl, exits: Exits, number: signal.Signals
) -> None:
    os.kill(os.getpid(), number)
    assert control.stop.wait(WAIT_S)
    assert control.reason == number.name
    time.sleep(0.1)
    assert exits.statuses == []


def test_a_second_signal_forces_the_exit_after_closing_the_bag(
    control: StopControl, exits: Exits
) -> None:
    closed: list[float] = []
    control.close_when_forced(closed.append)
    os.kill(os.getpid(), signal.SIGINT)
    assert control.stop.wait(WAIT_S)
    os.kill(os.getpid(), signal.SIGINT)
    assert exits.happened.wait(WAIT_S)
    assert exits.statuses == [128 + signal.SIGINT]
    assert closed == [FORCED_CLOSE_S]


def test_a_second_signal_works_while_the_main_thread_is_stuck(
    control: StopControl, exits: Exits
) -> None:
    """The main thread waits in a lock that only the forced exit releases: a handler on
    the main thread would have had its turn, but could not have ended the wait."""
    held = threading.Lock()
    held.acquire()
    control.close_when_forced(lambda seconds: held.release())

    def signal_twice() -> None:
        for _ in range(2):
            time.sleep(0.05)
            os.kill(os.getpid(), signal.SIGINT)

    threading.Thread(target=signal_twice).start()
    assert held.acquire(timeout=WAIT_S), "the forced exit never came"
    assert exits.happened.wait(WAIT_S)
    assert exits.statuses == [128 + signal.SIGINT]


def test_a_clean_stop_that_overruns_its_deadline_is_forced(
    exits: Exits, capfd: pytest.CaptureFixture[str], caplog: pytest.LogCaptureFixture
) -> None:
    with stop_on_signals(threading.Event(), deadline_s=0.2, exit_process=exits) as control:
        closed: list[float] = []
        control.close_when_forced(closed.append)
        control.request("requested by /test")
        began = time.monotonic()
        assert exits.happened.wait(WAIT_S)
        waited = time.monotonic() - began
    assert exits.statuses == [EXIT_STOP_FORCED]
    assert closed == [FORCED_CLOSE_S]
    assert waited >= 0.2
    assert "the stop (requested by /test) did not finish within 0.2 s" in caplog.text
    stacks = until(lambda: capfd.readouterr().err or None, "every thread's stack")
    assert "test_a_clean_stop_that_overruns_its_deadline_is_forced" in stacks


def test_a_clean_stop_done_in_time_is_not_forced(exits: Exits) -> None:
    with stop_on_signals(threading.Event(), deadline_s=0.2, exit_process=exits) as control:
        control.request("requested by /test")
        control.done()
        time.sleep(0.4)
    assert exits.statuses == []


def test_off_the_main_thread_requests_and_the_deadline_still_work(exits: Exits) -> None:
    seen: list[int] = []

    def run() -> None:
        with stop_on_signals(threading.Event(), deadline_s=0.1, exit_process=exits) as control:
            control.request("from a thread")
            exits.happened.wait(WAIT_S)
        seen.extend(exits.statuses)

    thread = threading.Thread(target=run)
    thread.start()
    thread.join(WAIT_S)
    assert seen == [EXIT_STOP_FORCED]


def test_the_previous_handlers_come_back(exits: Exits) -> None:
    numbers = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)
    before = [signal.getsignal(n) for n in numbers]
    with stop_on_signals(threading.Event(), exit_process=exits):
        assert signal.getsignal(signal.SIGINT) is not before[0]
    assert [signal.getsignal(n) for n in numbers] == before


def test_nohup_keeps_its_hangup_ignored(exits: Exits) -> None:
    previous = signal.signal(signal.SIGHUP, signal.SIG_IGN)
    try:
        with stop_on_signals(threading.Event(), exit_process=exits) as control:
            assert signal.getsignal(signal.SIGHUP) is signal.SIG_IGN
            os.kill(os.getpid(), signal.SIGHUP)
            assert not control.stop.wait(0.3)
    finally:
        signal.signal(signal.SIGHUP, previous)
