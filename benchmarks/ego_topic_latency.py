"""/Ego_topic latency of the running simulator against a rospy publisher, both received by
the same rospy subscriber (Debian's ROS 1, tcp_nodelay) on loopback.

    .venv/bin/python benchmarks/ego_topic_latency.py [--rounds 6] [--duration 15]
        [--warmup 2] [--rate 100] [--no-view]

Each round measures two publishers of /Ego_topic at --rate Hz, one after the other (the
order alternates from round to round, so neither always runs first):

- egosim: `egosim run --clock real` on the town with its default scenario, the
  ego_status row re-rated to --rate by a network settings file (the live view on, as
  `egosim run` starts, unless --no-view);
- rospy: a rospy node publishing an EgoVehicleStatus at --rate Hz, header.stamp = the
  wall time at publish.

The subscriber records arrival wall time - header.stamp for --duration s, after --warmup
s from its first message. Each publisher runs on its own fresh ROS master (free loopback
ports) and every process is stopped before the next. Prints one Markdown row per round and
publisher, then the median over rounds of egosim's median and p99 divided by rospy's in
the same round, with the load average before and after.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import queue
import signal
import statistics
import subprocess
import sys
import tempfile
import threading
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from loopback import free_port

from egosim.msgs import get_profile
from egosim.ros1 import Master

ROS_PYTHON = "/usr/bin/python3"
PEERS = Path(__file__).resolve().parent.parent / "tests" / "ros1" / "peers"
TOPIC = "/Ego_topic"
#: Longest a simulator or a peer may take to start, and a round beyond its duration (s).
START_DEADLINE_S = 60.0
ROUND_SLACK_S = 30.0


@dataclass(frozen=True)
class Latency:
    received: int
    median_ms: float
    p99_ms: float


class Lines:
    """A process's stdout lines, read on a thread so every wait can have a deadline."""

    def __init__(self, process: subprocess.Popen[str], name: str) -> None:
        self.process = process
        self.name = name
        self._lines: queue.Queue[str | None] = queue.Queue()
        threading.Thread(target=self._read, daemon=True).start()

    def _read(self) -> None:
        assert self.process.stdout is not None
        for line in self.process.stdout:
            self._lines.put(line)
        self._lines.put(None)

    def wait_for(self, accept: Callable[[str], Any], timeout: float, what: str) -> Any:
        """The first non-None `accept(line)` within `timeout` s."""
        deadline = time.monotonic() + timeout
        while (remaining := deadline - time.monotonic()) > 0:
            try:
                line = self._lines.get(timeout=remaining)
            except queue.Empty:
                break
            if line is None:
                raise RuntimeError(f"{self.name} exited before {what}")
            if (found := accept(line)) is not None:
                return found
        raise TimeoutError(f"no {what} within {timeout:g} s from {self.name}")


def json_with(key: str) -> Callable[[str], dict[str, Any] | None]:
    def accept(line: str) -> dict[str, Any] | None:
        if line.startswith("{") and key in (data := json.loads(line)):
            return data  # type: ignore[no-any-return]
        return None

    return accept


@contextlib.contextmanager
def started(args: list[str], env: dict[str, str]) -> Iterator[Lines]:
    """`args` in a process group of its own, interrupted (then killed) on leaving."""
    process = subprocess.Popen(
        args,
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.DEVNULL,
        text=True,
        start_new_session=True,
    )
    try:
        yield Lines(process, " ".join(args[:3]))
    finally:
        with contextlib.suppress(ProcessLookupError):
            os.killpg(process.pid, signal.SIGINT)
        try:
            process.wait(5)
        except subprocess.TimeoutExpired:
            with contextlib.suppress(ProcessLookupError):
                os.killpg(process.pid, signal.SIGKILL)
            process.wait()


@contextlib.contextmanager
def ros_master() -> Iterator[dict[str, str]]:
    """A fresh master on a free loopback port; the environment of the processes on it."""
    with tempfile.TemporaryDirectory() as home:
        master = Master(f"http://127.0.0.1:{free_port()}/").start()
        env = {k: v for k, v in os.environ.items() if not k.startswith("ROS_")}
        env.update(
            ROS_MASTER_URI=master.uri,
            ROS_IP="127.0.0.1",
            ROS_HOME=home,
            ROS_LOG_DIR=home,
            PYTHONUNBUFFERED="1",
        )
        try:
            yield env
        finally:
            master.shutdown()


def listen(env: dict[str, str], warmup: float, duration: float) -> Latency:
    """Latencies of TOPIC, once something publishes it (the caller starts that)."""
    args = [ROS_PYTHON, str(PEERS / "latency_listener.py"), TOPIC]
    args += ["--warmup", str(warmup), "--duration", str(duration)]
    with started(args, env) as listener:
        listener.wait_for(json_with("event"), START_DEADLINE_S, "subscription")
        summary = listener.wait_for(
            json_with("latencies_ns"), warmup + duration + ROUND_SLACK_S, "latency summary"
        )
    latencies = sorted(summary["latencies_ns"])
    count = len(latencies)
    return Latency(
        received=count,
        median_ms=statistics.median(latencies) / 1e6,
        p99_ms=latencies[min(count - 1, int(count * 0.99))] / 1e6,
    )


def egosim_round(options: argparse.Namespace, network: Path) -> Latency:
    with ros_master() as env:
        args = [sys.executable, "-m", "egosim", "run", "--clock", "real", "--map", "town"]
        args += ["--network", str(network), "--log-level", "WARNING"]
        args += ["--no-view"] if options.no_view else ["--view-port", "0"]
        with started(args, env) as simulator:
            simulator.wait_for(
                lambda line: line.strip() == "egosim: ready" or None,
                START_DEADLINE_S,
                "'egosim: ready'",
            )
            return listen(env, options.warmup, options.duration)


def rospy_round(options: argparse.Namespace, definition: Path) -> Latency:
    with ros_master() as env:
        args = [ROS_PYTHON, str(PEERS / "stamped_talker.py"), TOPIC]
        args += ["morai_msgs/EgoVehicleStatus", str(definition), "--rate", str(options.rate)]
        args += ["--duration", str(options.warmup + options.duration + ROUND_SLACK_S)]
        with started(args, env):
            return listen(env, options.warmup, options.duration)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--rounds", type=int, default=6)
    parser.add_argument("--duration", type=float, default=15.0, help="s recorded per run")
    parser.add_argument("--warmup", type=float, default=2.0, help="s not recorded first")
    parser.add_argument("--rate", type=float, default=100.0, help="Hz")
    parser.add_argument("--no-view", action="store_true", help="egosim run --no-view")
    options = parser.parse_args()
    ego = get_profile("26.r1").message("morai_msgs/EgoVehicleStatus")
    load_before = os.getloadavg()
    with tempfile.TemporaryDirectory() as folder:
        network = Path(folder, "network.yaml")
        network.write_text(f"rows:\n  ego_status: {{rate_hz: {options.rate:g}}}\n")
        definition = Path(folder, "EgoVehicleStatus.msg")
        definition.write_text(ego.definition)
        runs: dict[str, Callable[[], Latency]] = {
            "egosim": lambda: egosim_round(options, network),
            "rospy": lambda: rospy_round(options, definition),
        }
        print(
            f"/Ego_topic at {options.rate:g} Hz, {options.duration:g} s per run after "
            f"{options.warmup:g} s, view {'off' if options.no_view else 'on'}\n"
        )
        print("| round | publisher | received | median (ms) | p99 (ms) |")
        print("|---:|---|---:|---:|---:|")
        ratios: list[tuple[float, float]] = []
        for n in range(options.rounds):
            order = ("egosim", "rospy") if n % 2 == 0 else ("rospy", "egosim")
            results = {}
            for publisher in order:
                result = results[publisher] = runs[publisher]()
                print(
                    f"| {n + 1} | {publisher} | {result.received} "
                    f"| {result.median_ms:.3f} | {result.p99_ms:.3f} |",
                    flush=True,
                )
            egosim, rospy = results["egosim"], results["rospy"]
            ratios.append((egosim.median_ms / rospy.median_ms, egosim.p99_ms / rospy.p99_ms))
    load_after = os.getloadavg()
    median_ratio = statistics.median(ratio for ratio, _ in ratios)
    p99_ratio = statistics.median(ratio for _, ratio in ratios)
    print(
        f"\negosim / rospy, median over {options.rounds} rounds: median {median_ratio:.2f}x, "
        f"p99 {p99_ratio:.2f}x; load average {load_before[0]:.2f} before, "
        f"{load_after[0]:.2f} after"
    )


if __name__ == "__main__":
    main()
