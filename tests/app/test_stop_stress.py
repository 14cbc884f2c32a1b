"""Stops at random moments, many of them: `app.runner.run` in this process (so a run costs
tenths of a second, not a process start), stopped by SIGINT, SIGTERM and the Slave API's
shutdown (what `rosnode kill` calls; Debian's rosnode itself too when it is installed)
while it records, replays, switches control modes, runs in sync mode or has a page on its
view. Every stop must end the run cleanly within the README's 2 s and leave an indexed bag.

EGOSIM_STRESS_STOPS sets the number of stops (40 by default). The longer run over
`egosim run` processes, double signals included, is
benchmarks/stop_stress.py (docs/BENCHMARKS.md); forced exits are in tests/e2e/test_stops.py.
"""

from __future__ import annotations

import os
import random
import signal
import threading
import time
from collections.abc import Iterator
from pathlib import Path
from types import FrameType

import pytest

from egosim.app.attachments import Attachment, RunningSimulator
from egosim.app.exit_codes import EXIT_OK
from egosim.app.options import RunOptions
from egosim.app.runner import run
from egosim.bridge import ClockMode
from egosim.view import ViewOptions, live_view
from egosim.view.attach import LiveView
from tests.conftest import free_port
from tests.debian_ros import missing_ros_reason
from tests.replay.drive import record_drive
from tests.stop_stress import (
    STOP_BOUND_S,
    Client,
    PageWatcher,
    Plan,
    StopKind,
    StopResult,
    bag_problem,
    provide_replay_bag,
    random_plan,
    send_stop,
    summary,
)

#: Stops per run: 40 in `make test`; EGOSIM_STRESS_STOPS=300 for the long form (README,
#: docs/BENCHMARKS.md). The plans come from one seed, so the first 40 of a long run are
#: the default run's.
STOPS = int(os.environ.get("EGOSIM_STRESS_STOPS", "40"))
SEED = 29
#: The runs' own stop handling must see every signal: one reaching this handler instead
#: (sent before the run installed its own, or after it restored this one) is a lost stop.
STRAY: list[int] = []
#: A small map and no camera: a run is up in a few hundredths of a second.
NETWORK = "rows: {camera: {enabled: false}}\n"


def note_stray(number: int, frame: FrameType | None) -> None:
    STRAY.append(number)


@pytest.fixture
def signals_to_this_test() -> Iterator[None]:
    """SIGINT and SIGTERM sent to this process never end the test session."""
    previous = {n: signal.signal(n, note_stray) for n in (signal.SIGINT, signal.SIGTERM)}
    try:
        yield
    finally:
        for number, handler in previous.items():
            signal.signal(number, handler)


class _Up:
    """Told when the run is up (attachments are built right before `egosim: ready`)."""

    def __init__(self) -> None:
        self.event = threading.Event()
        self.view_url: str | None = None

    def attach(self, running: RunningSimulator) -> Attachment:
        self.event.set()
        return self

    def close(self) -> None:
        pass


def watched_view(up: _Up) -> object:
    view = live_view(ViewOptions(port=0))

    def attach(running: RunningSimulator) -> Attachment:
        attached = view(running)
        if isinstance(attached, LiveView):
            up.view_url = f"ws://127.0.0.1:{attached.server.port}/ws"
        return attached

    return attach


def handlers_installed() -> bool:
    return signal.getsignal(signal.SIGINT) is not note_stray


def stop_once(plan: Plan, data_root: Path, network: Path, number: int) -> StopResult:
    rng = random.Random(plan.seed)
    master_uri = f"http://127.0.0.1:{free_port()}/"
    os.environ["ROS_MASTER_URI"] = master_uri
    bag = data_root / f"stop{number}.bag"
    up = _Up()
    attach = [*([watched_view(up)] if plan.view else []), up.attach]
    options = RunOptions(
        map="straight",
        network=network,
        clock=ClockMode(plan.clock),
        record=bag,
        data_roots=(data_root,),
        log_level="WARNING",
    )
    stopped_at: list[float] = []
    failure: list[str] = []

    def kill(number: int) -> None:
        os.kill(os.getpid(), number)

    def drive() -> None:
        try:
            if plan.during_startup:
                deadline = time.monotonic() + 30
                while not handlers_installed() and time.monotonic() < deadline:
                    time.sleep(0.001)
                time.sleep(rng.uniform(0.0, 0.05))
                stopped_at.append(send_stop(plan.stop, master_uri, dict(os.environ), kill))
                return
            if not up.event.wait(30):
                failure.append("the run did not come up within 30 s")
                return
            client = Client(master_uri, f"stress{number}", rng)
            page = PageWatcher(up.view_url, rng) if up.view_url else None
            try:
                for action in plan.actions:
                    client.act(action)
                flight = client.in_flight(plan.in_flight) if plan.in_flight else None
                time.sleep(rng.uniform(0.0, 0.05))
                stopped_at.append(send_stop(plan.stop, master_uri, dict(os.environ), kill))
                if flight is not None:
                    flight.join(STOP_BOUND_S * 3)
            finally:
                if page is not None:
                    page.close()
                client.close()
        except Exception as error:  # reported with the plan, below
            failure.append(f"the client failed: {error!r}")

    driver = threading.Thread(target=drive, name="stress driver")
    driver.start()
    status = run(options, attach)
    ended = time.monotonic()
    driver.join(30)
    seconds = max(ended - stopped_at[0], 0.0) if stopped_at else float("inf")
    problems = list(failure)
    if status != EXIT_OK:
        problems.append(f"exit status {status}")
    if seconds > STOP_BOUND_S:
        problems.append(f"took {seconds:.2f} s")
    if bag.exists() or not plan.during_startup:  # stopped before the bag was opened: none
        problems.append(bag_problem(bag) or "")
    return StopResult(plan, seconds, status, "; ".join(p for p in problems if p) or None)


@pytest.mark.usefixtures("signals_to_this_test")
def test_every_stop_at_a_random_moment_is_clean_prompt_and_leaves_an_indexed_bag(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("ROS_IP", "127.0.0.1")
    data_root = tmp_path / "data"
    data_root.mkdir()
    provide_replay_bag(data_root, record_drive(tmp_path / "drive.bag"))
    network = tmp_path / "network.yaml"
    network.write_text(NETWORK)
    kinds = {StopKind.SIGINT: 3.0, StopKind.SIGTERM: 2.0, StopKind.SLAVE_SHUTDOWN: 2.0}
    if missing_ros_reason() is None:
        kinds[StopKind.ROSNODE_KILL] = 0.5  # Debian's rosnode takes a second to start
    rng = random.Random(SEED)
    results = []
    for number in range(STOPS):
        plan = random_plan(rng, kinds, startup_share=0.1)
        results.append(stop_once(plan, data_root, network, number))
        (data_root / f"stop{number}.bag").unlink(missing_ok=True)
    print(summary(results))
    failed = [f"{r.plan.describe()}: {r.problem}" for r in results if r.problem is not None]
    assert not failed, f"{len(failed)} of {STOPS} stops failed:\n" + "\n".join(failed)
    assert not STRAY, f"signals that no run saw: {STRAY}"
