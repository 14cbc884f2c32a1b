"""A server's connection threads: each connection in a thread of its own, a finished
thread taking the next connection instead of a new thread starting, none left waiting
once the server closes."""

from __future__ import annotations

import threading

from egosim.ros1.handler_threads import HandlerThreads
from tests.waiting import until

DEADLINE_S = 30.0


def test_a_thread_whose_job_ended_takes_the_next_one_under_its_name() -> None:
    threads = HandlerThreads(idle_s=DEADLINE_S)
    ran: list[tuple[int, str]] = []
    done = threading.Semaphore(0)

    def job() -> None:
        ran.append((threading.get_ident(), threading.current_thread().name))
        done.release()

    try:
        for k in range(5):
            threads.run(job, f"connection {k}")
            assert done.acquire(timeout=DEADLINE_S), f"job {k} did not run"
            until(lambda: threads.waiting, f"the thread to wait after job {k}")
    finally:
        threads.close()
    assert len({ident for ident, _ in ran}) == 1
    assert [name for _, name in ran] == [f"connection {k}" for k in range(5)]


def test_a_job_never_waits_for_another_to_end() -> None:
    threads = HandlerThreads(idle_s=DEADLINE_S)
    release = threading.Event()
    started = threading.Semaphore(0)

    def held() -> None:
        started.release()
        release.wait(DEADLINE_S)

    try:
        for k in range(4):  # each holds its thread, as a persistent connection does
            threads.run(held, f"held {k}")
        for k in range(4):
            assert started.acquire(timeout=DEADLINE_S), f"only {k} of 4 jobs began"
    finally:
        release.set()
        threads.close()


def test_closing_ends_the_waiting_threads_and_a_failing_job_ends_only_itself() -> None:
    threads = HandlerThreads(idle_s=DEADLINE_S)
    done = threading.Event()
    names = ("failing", "after it")

    def failing() -> None:
        raise RuntimeError("a handler's bug")

    threads.run(failing, names[0])
    until(lambda: threads.waiting, "the thread to wait after the failing job")
    threads.run(done.set, names[1])
    assert done.wait(DEADLINE_S), "the job after a failing one did not run"
    until(lambda: threads.waiting, "the thread to wait again")
    threads.close()
    until(
        lambda: not any(t.name in names for t in threading.enumerate()),
        "the waiting thread to end once closed",
    )


def test_a_thread_waits_only_so_long_for_the_next_job() -> None:
    threads = HandlerThreads(idle_s=0.05)
    threads.run(lambda: None, "short-lived")
    until(
        lambda: not any(t.name == "short-lived" for t in threading.enumerate()),
        "the idle thread to end by itself",
    )
    threads.close()
