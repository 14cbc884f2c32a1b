"""The inbox the loop waits on: a wait returns at its timeout however signals interrupt it,
and no call waits on a loop that has stopped (a Ctrl-C that stopped nothing)."""

from __future__ import annotations

import os
import signal
import threading
import time
from collections.abc import Iterator
from concurrent.futures import ThreadPoolExecutor

import pytest

from egosim.app.inbox import Inbox, LoopStoppedError

#: A wait of 10 ms that took this long did not return at its timeout: something else (the
#: next post, every RESCUE_S) ended it. Far above what a loaded machine delays a thread.
STUCK_S = 0.5
RESCUE_S = 2.0


@pytest.fixture
def signals_every_few_ms() -> Iterator[None]:
    """SIGINT to this process every 7 ms (a no-op handler meanwhile), while another thread
    keeps the interpreter busy: the interrupted wait then takes the GIL back late, as the
    loop does among egosim's transport threads."""
    previous = signal.signal(signal.SIGINT, lambda *_: None)
    done = threading.Event()

    def interrupt() -> None:
        while not done.wait(0.007):
            os.kill(os.getpid(), signal.SIGINT)

    def spin() -> None:
        while not done.is_set():
            pass

    threads = [threading.Thread(target=interrupt), threading.Thread(target=spin)]
    for thread in threads:
        thread.start()
    try:
        yield
    finally:
        done.set()
        for thread in threads:
            thread.join()
        signal.signal(signal.SIGINT, previous)


@pytest.mark.usefixtures("signals_every_few_ms")
def test_a_wait_returns_at_its_timeout_however_signals_interrupt_it() -> None:
    inbox = Inbox()
    rescue = threading.Event()

    def post_now_and_then() -> None:
        # A wait that missed its timeout is ended only by a post: these bound the test.
        while not rescue.wait(RESCUE_S):
            inbox.post(lambda: None)

    rescuer = threading.Thread(target=post_now_and_then)
    rescuer.start()
    waits: list[float] = []
    try:
        end = time.monotonic() + 3.0
        while time.monotonic() < end:
            began = time.monotonic()
            inbox.wait(0.01)
            waits.append(time.monotonic() - began)
    finally:
        rescue.set()
        rescuer.join()
    stuck = [round(w, 3) for w in waits if w > STUCK_S]
    assert not stuck, f"{len(stuck)} of {len(waits)} waits of 10 ms lasted {stuck} s"


def test_a_call_after_close_is_refused_at_once() -> None:
    inbox = Inbox()
    inbox.close()
    began = time.monotonic()
    with pytest.raises(LoopStoppedError):
        inbox.call(lambda: 1, timeout=30)
    assert time.monotonic() - began < 1.0


def test_calls_racing_a_close_are_answered_or_refused_never_left_waiting() -> None:
    """Callers keep calling while the loop serves them and then stops: each call gets its
    result or LoopStoppedError, none waits out its timeout."""
    inbox = Inbox()

    def caller() -> list[str]:
        outcomes: list[str] = []
        while "refused" not in outcomes and "left waiting" not in outcomes:
            try:
                outcomes.append(str(inbox.call(lambda: "ran", timeout=5.0)))
            except LoopStoppedError:
                outcomes.append("refused")
            except TimeoutError:
                outcomes.append("left waiting")
        return outcomes

    with ThreadPoolExecutor(8) as pool:
        callers = [pool.submit(caller) for _ in range(8)]
        end = time.monotonic() + 0.3
        while time.monotonic() < end:
            inbox.wait(0.001)
        inbox.close()
        outcomes = [c.result(timeout=30) for c in callers]
    assert all(o[-1] == "refused" for o in outcomes), outcomes
    assert any("ran" in o for o in outcomes)


def test_a_call_returns_what_the_work_returned_and_raises_what_it_raised() -> None:
    inbox = Inbox()
    stop = threading.Event()

    def loop() -> None:
        while not stop.is_set():
            inbox.wait(0.01)

    def fail() -> None:
        raise KeyError("no such row")

    thread = threading.Thread(target=loop)
    thread.start()
    try:
        assert inbox.call(lambda: 42, timeout=30) == 42
        error = ValueError("a value, not raised")
        assert inbox.call(lambda: error, timeout=30) is error
        with pytest.raises(KeyError, match="no such row"):
            inbox.call(fail, timeout=30)
    finally:
        stop.set()
        thread.join()


def test_a_call_the_loop_never_runs_times_out() -> None:
    inbox = Inbox()
    began = time.monotonic()
    with pytest.raises(TimeoutError):
        inbox.call(lambda: 1, timeout=0.2)
    assert time.monotonic() - began < 5.0, "the call waited far past its timeout"
