"""Hundreds of `egosim run` processes stopped at random moments, timed.

Each run records (`--record`), on the town with its camera, in a random clock mode, with
the view watched by a page in some; a client switches control modes, replays a bag,
ticks in sync mode and sends commands (tests/stop_stress.py), and the run is stopped
during start-up or at a random moment after, by SIGINT, SIGTERM, Debian's `rosnode kill`,
the Slave API's shutdown call or SIGINT twice, sometimes with a service call in flight.
Every stop must end the process within 2 s (README) with an indexed bag (every tenth is
also read by Debian's `rosbag info`): cleanly (status 0), or by the forced exit when the
clean stop overran its 1.4 s (4) or a second SIGINT came (130), both counted.

Usage: .venv/bin/python benchmarks/stop_stress.py [--stops 300] [--seed 29]
"""

from __future__ import annotations

import argparse
import logging
import os
import random
import re
import signal
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

from loopback import free_port

from egosim.app.exit_codes import EXIT_STOP_FORCED

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # the tests' stress harness

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
    rosbag_says_indexed,
    send_stop,
    summary,
)

KINDS = {
    StopKind.SIGINT: 3.0,
    StopKind.SIGTERM: 2.0,
    StopKind.ROSNODE_KILL: 1.0,
    StopKind.SLAVE_SHUTDOWN: 1.0,
    StopKind.SECOND_SIGINT: 1.0,
}
UP_TIMEOUT_S = 60.0
EXIT_TIMEOUT_S = 30.0


class Simulator:
    """One `egosim run` process; its stdout read on a thread."""

    def __init__(self, plan: Plan, root: Path, bag: Path, master_uri: str) -> None:
        view = ["--view-port", "0"] if plan.view else ["--no-view"]
        args = ["--record", str(bag), "--data-root", str(root), "--clock", plan.clock, *view]
        self.env = dict(os.environ, ROS_MASTER_URI=master_uri, ROS_IP="127.0.0.1")
        self.log = (root / f"{bag.stem}.log").open("wb")
        self.popen = subprocess.Popen(
            [sys.executable, "-m", "egosim", "run", *args],
            env=self.env,
            stdout=subprocess.PIPE,
            stderr=self.log,
            text=True,
        )
        self.ready = threading.Event()
        self.view_url: str | None = None
        threading.Thread(target=self._read, daemon=True).start()

    def _read(self) -> None:
        assert self.popen.stdout is not None
        for line in self.popen.stdout:
            if match := re.match(r"^egosim: view at http(\S+)$", line):
                self.view_url = f"ws{match.group(1)}ws"
            elif line.strip() == "egosim: ready":
                self.ready.set()

    def kill(self, number: int) -> None:
        self.popen.send_signal(number)


def stop_once(plan: Plan, root: Path, number: int) -> StopResult:
    rng = random.Random(plan.seed)
    bag = root / f"stop{number}.bag"
    master_uri = f"http://127.0.0.1:{free_port()}/"
    simulator = Simulator(plan, root, bag, master_uri)
    problem = None
    sent = time.monotonic()
    try:
        if plan.during_startup:
            # Once its first line is logged (its master starting) egosim handles signals;
            # before, Python is still importing it.
            until_logged(root / f"{bag.stem}.log")
            time.sleep(rng.uniform(0.0, 0.5))
            sent = send_stop(plan.stop, master_uri, simulator.env, simulator.kill)
        elif not simulator.ready.wait(UP_TIMEOUT_S):
            problem = "not up in time"
        else:
            sent = drive_and_stop(plan, simulator, master_uri, rng)
        status = simulator.popen.wait(EXIT_TIMEOUT_S)
    except subprocess.TimeoutExpired:
        simulator.popen.kill()
        status = simulator.popen.wait()
        problem = f"still running {EXIT_TIMEOUT_S:.0f} s after the stop"
    seconds = max(time.monotonic() - sent, 0.0)
    simulator.log.close()
    # 0: a clean stop; EXIT_STOP_FORCED: one that overran its deadline, ended (the bag
    # closed) by the forced exit; 130: the second SIGINT's forced exit.
    forced = status == EXIT_STOP_FORCED or status == 128 + signal.SIGINT
    allowed = {0, EXIT_STOP_FORCED}
    if plan.stop is StopKind.SECOND_SIGINT:
        allowed.add(128 + signal.SIGINT)
    problems = [problem] if problem else []
    if status not in allowed:
        problems.append(f"exit status {status}")
    if seconds > STOP_BOUND_S:
        problems.append(f"took {seconds:.2f} s")
    # A bag is checked whatever else went wrong: a slow stop must still have closed it.
    if bag.exists() or not plan.during_startup:
        problems.append(bag_problem(bag) or "")
    if bag.exists() and number % 10 == 0 and not rosbag_says_indexed(bag):
        problems.append("Debian's rosbag info does not read it as indexed")
    problem = "; ".join(p for p in problems if p) or None
    return StopResult(plan, seconds, status, problem, forced)


def until_logged(log: Path) -> None:
    deadline = time.monotonic() + UP_TIMEOUT_S
    while log.stat().st_size == 0 and time.monotonic() < deadline:
        time.sleep(0.01)


def drive_and_stop(plan: Plan, simulator: Simulator, master_uri: str, rng: random.Random) -> float:
    client = Client(master_uri, f"stress{time.monotonic_ns()}", rng)
    page = PageWatcher(simulator.view_url, rng) if simulator.view_url else None
    try:
        for action in plan.actions:
            client.act(action)
        if plan.in_flight:
            client.in_flight(plan.in_flight)
        time.sleep(rng.uniform(0.0, 0.05))
        return send_stop(plan.stop, master_uri, simulator.env, simulator.kill)
    finally:
        if page is not None:
            page.close()
        client.close()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--stops", type=int, default=300)
    parser.add_argument("--seed", type=int, default=29)
    args = parser.parse_args()
    # The clients' own nodes complain when a stopped simulator takes its master along.
    logging.basicConfig(level=logging.ERROR)
    rng = random.Random(args.seed)
    results = []
    with tempfile.TemporaryDirectory() as folder:
        root = Path(folder)
        provide_replay_bag(root, record_drive(root / "drive.bag"))
        for number in range(args.stops):
            result = stop_once(random_plan(rng, KINDS, startup_share=0.1), root, number)
            results.append(result)
            if result.problem is not None or result.forced:
                log = (root / f"stop{number}.log").read_text(errors="replace")
                what = "FAILED" if result.problem else f"forced ({result.status})"
                print(f"{what} {result.plan.describe()}: {result.problem or ''}\n{log[-2000:]}")
            (root / f"stop{number}.bag").unlink(missing_ok=True)
            if (number + 1) % 25 == 0:
                print(f"{number + 1} stops", flush=True)
    print(summary(results))
    seconds = sum(r.status == 128 + signal.SIGINT for r in results)
    overran = sum(r.status == EXIT_STOP_FORCED for r in results)
    print(f"forced: {seconds} by the second SIGINT (130), {overran} by the deadline (4)")
    if any(r.problem is not None for r in results):
        raise SystemExit(1)


if __name__ == "__main__":
    main()
