"""Stopping egosim at random moments: what a run does before it is stopped (a client's
mode switches, replays, sync-mode ticks, commands; a browser on the view), how it is
stopped, and what every stop must leave behind (an indexed bag, within the bound).

Shared by tests/app/test_stop_stress.py (runs in the test's own process) and
benchmarks/stop_stress.py (hundreds of `egosim run` processes).
"""

from __future__ import annotations

import asyncio
import contextlib
import enum
import json
import random
import shutil
import signal
import subprocess
import threading
import time
import xmlrpc.client
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml
from rosbags.rosbag1 import Reader, ReaderError

from egosim.msgs import get_profile
from egosim.replay import needs_repair
from egosim.ros1 import Node, Ros1Error
from egosim.ros1.rpc import call as rpc_call
from tests.debian_ros import ROS_PYTHON

#: README: a stop (Ctrl-C, SIGTERM, `rosnode kill`) exits within 2 s.
STOP_BOUND_S = 2.0
#: The bag a replay action loads, in the run's data root.
REPLAY_BAG = "replay.bag"
ROSNODE = "/usr/bin/rosnode"

PROFILE = get_profile("26.r1")
EVENT = PROFILE.service("morai_msgs/MoraiEventCmdSrv")
SIM_PROC = PROFILE.service("morai_msgs/MoraiSimProcSrv")
SYNC = PROFILE.service("morai_msgs/MoraiSyncModeCmdSrv")
TICK = PROFILE.service("morai_msgs/MoraiWaitForTickSrv")
CTRL = PROFILE.message("morai_msgs/CtrlCmd")
CALL_TIMEOUT_S = 5.0
#: Two signals sent at once are one: the kernel keeps one pending per kind.
SECOND_SIGNAL_AFTER_S = 0.05


class StopKind(enum.Enum):
    SIGINT = "SIGINT"
    SIGTERM = "SIGTERM"
    ROSNODE_KILL = "rosnode kill"  # Debian's rosnode, under the ROS Python
    SLAVE_SHUTDOWN = "shutdown call"  # the Slave API call rosnode makes, made directly
    SECOND_SIGINT = "SIGINT twice"


ACTIONS = (
    "autopilot",  # EventCmd ctrl_mode 4
    "external",  # EventCmd ctrl_mode 3
    "replay",  # load and play REPLAY_BAG
    "replay_stop",
    "sync_start",
    "sync_ticks",
    "sync_stop",
    "command",  # one /ctrl_cmd
    "pause",  # EventCmd set_pause on or off
    "wait",
)


@dataclass
class Plan:
    """What one run does before its stop, and how it is stopped."""

    clock: str
    view: bool
    actions: list[str]
    stop: StopKind
    in_flight: str | None  # an action whose call is under way as the stop arrives
    during_startup: bool  # stopped before the run is up
    seed: int

    def describe(self) -> str:
        when = "during start-up" if self.during_startup else f"after {self.actions}"
        flight = f", {self.in_flight} in flight" if self.in_flight else ""
        view = ", view watched" if self.view else ""
        return f"{self.stop.value} {when}{flight} (clock {self.clock}{view}, seed {self.seed})"


def random_plan(rng: random.Random, kinds: dict[StopKind, float], startup_share: float) -> Plan:
    """A plan; `kinds` weighs the ways to stop, `startup_share` is the share stopped while
    the run starts (by a signal: no node to shut down yet)."""
    seed = rng.randrange(2**31)
    during_startup = rng.random() < startup_share
    return Plan(
        clock=rng.choice(("real", "real", "sim", "sync")),
        view=rng.random() < 0.4,
        actions=[] if during_startup else [rng.choice(ACTIONS) for _ in range(rng.randint(0, 6))],
        stop=(
            rng.choice((StopKind.SIGINT, StopKind.SIGTERM))
            if during_startup
            else rng.choices(list(kinds), weights=list(kinds.values()))[0]
        ),
        in_flight=None if during_startup or rng.random() < 0.5 else rng.choice(ACTIONS[:7]),
        during_startup=during_startup,
        seed=seed,
    )


@dataclass
class Client:
    """A client of the simulator (egosim's own ROS node: quick to start, so a stress test
    can afford hundreds), acting as a driving stack would."""

    master_uri: str
    name: str
    rng: random.Random
    node: Node = field(init=False)
    frame: int = 0
    synced: bool = False

    def __post_init__(self) -> None:
        self.node = Node(
            self.name, master_uri=self.master_uri, embedded_master="never", rosout_logger=None
        )
        self.commands = self.node.advertise("/ctrl_cmd", CTRL)

    def act(self, action: str) -> None:
        """One action; a refused or failed call is part of the game (the run may be
        stopping), never an error of the harness."""
        with contextlib.suppress(Ros1Error, OSError):
            self._act(action)

    def _act(self, action: str) -> None:
        if action == "autopilot":
            self._call("/Service_MoraiEventCmd", EVENT, option=1, ctrl_mode=4)
        elif action == "external":
            self._call("/Service_MoraiEventCmd", EVENT, option=1, ctrl_mode=3)
        elif action == "pause":
            self._call("/Service_MoraiEventCmd", EVENT, option=8, set_pause=self.rng.random() < 0.5)
        elif action == "replay":
            self._call(
                "/Morai_SimProc",
                SIM_PROC,
                sim_process_status=1,
                replay_option=0x1001,
                rosbag_file_name=REPLAY_BAG,
                replay_speed=self.rng.choice((1, 2, 4)),
            )
        elif action == "replay_stop":
            self._call("/Morai_SimProc", SIM_PROC, sim_process_status=32, replay_option=0)
        elif action == "sync_start":
            reply = self._call(
                "/SyncModeCmd", SYNC, user_id="stress", start_sync_mode=True, time_step=20
            )
            self.synced, self.frame = True, reply.response.frame
        elif action == "sync_ticks":
            self.frame += self.rng.randint(1, 30)
            self._call("/SyncModeWaitForTick", TICK, user_id="stress", frame=self.frame)
        elif action == "sync_stop":
            self._call("/SyncModeCmd", SYNC, user_id="stress", start_sync_mode=False)
            self.synced = False
        elif action == "command":
            velocity = self.rng.uniform(0.0, 40.0)
            self.commands.publish(CTRL.serialize(CTRL.new(longlCmdType=2, velocity=velocity)))
        else:
            time.sleep(self.rng.uniform(0.0, 0.2))

    def _call(self, service: str, srv: Any, **fields: Any) -> Any:
        proxy = self.node.service_proxy(service, srv)
        request = srv.request.new()
        for name, value in fields.items():
            setattr(request.request, name, value)
        reply = proxy.call(srv.request.serialize(request), timeout=CALL_TIMEOUT_S)
        return srv.response.deserialize(reply)

    def in_flight(self, action: str) -> threading.Thread:
        """`action` on a thread of its own, begun now."""
        thread = threading.Thread(target=self.act, args=(action,), daemon=True)
        thread.start()
        return thread

    def close(self) -> None:
        self.node.shutdown("stress client done")


class PageWatcher:
    """A browser's part on the view's websocket (aiohttp's client): it takes every frame
    and now and then asks for a pause, a step or a resume."""

    def __init__(self, url: str, rng: random.Random) -> None:
        self.url = url
        self.rng = random.Random(rng.randrange(2**31))
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, name="page watcher", daemon=True)
        self._thread.start()

    def _run(self) -> None:
        import aiohttp  # noqa: PLC0415 - only the runs with a view need it

        async def watch() -> None:
            async with aiohttp.ClientSession() as session, session.ws_connect(self.url) as ws:
                while not self._stop.is_set():
                    with contextlib.suppress(asyncio.TimeoutError):
                        message = await ws.receive(timeout=0.1)
                        if message.type in (aiohttp.WSMsgType.CLOSE, aiohttp.WSMsgType.CLOSED):
                            return
                    if self.rng.random() < 0.1:
                        op = self.rng.choice(("pause", "resume", "step"))
                        await ws.send_str(json.dumps({"op": op}))

        with contextlib.suppress(Exception):  # the simulator going away ends the page
            asyncio.run(watch())

    def close(self) -> None:
        self._stop.set()
        self._thread.join(STOP_BOUND_S)


def shutdown_by_slave_api(master_uri: str, node: str = "/egosim") -> None:
    """What `rosnode kill` does: look the node up, call its Slave API's shutdown."""
    _, _, uri = xmlrpc.client.ServerProxy(master_uri).lookupNode("/stress", node)
    rpc_call(uri, "shutdown", "/stress", "stress test", timeout=CALL_TIMEOUT_S)


def rosnode_kill(master_uri: str, env: dict[str, str], node: str = "/egosim") -> None:
    """Debian's `rosnode kill NODE`; returns once it has (it waits for the node's answer)."""
    subprocess.run(
        [ROS_PYTHON, ROSNODE, "kill", node],
        env={**env, "ROS_MASTER_URI": master_uri},
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        timeout=60,
        check=False,
    )


def send_stop(kind: StopKind, master_uri: str, env: dict[str, str], kill: Any) -> float:
    """Stop a run the way `kind` says (`kill(signal)` signals the simulator); the moment
    (time.monotonic) the stop counts from: when it was sent, or for `rosnode kill` when
    the command returned, the simulator having answered it (the second rosnode takes to
    start, under the ROS Python, is not the simulator's)."""
    sent = time.monotonic()
    if kind is StopKind.SIGINT:
        kill(signal.SIGINT)
    elif kind is StopKind.SIGTERM:
        kill(signal.SIGTERM)
    elif kind is StopKind.SECOND_SIGINT:
        kill(signal.SIGINT)
        time.sleep(SECOND_SIGNAL_AFTER_S)
        kill(signal.SIGINT)
    elif kind is StopKind.SLAVE_SHUTDOWN:
        shutdown_by_slave_api(master_uri)
    else:
        rosnode_kill(master_uri, env)
        sent = time.monotonic()
    return sent


def bag_problem(path: Path) -> str | None:
    """What is wrong with a bag a stopped run leaves (None: complete and indexed)."""
    if not path.exists():
        return f"{path} was not written"
    if needs_repair(path):
        return f"{path} is not indexed (the recording was not closed)"
    try:
        with Reader(path) as reader:
            sum(1 for _ in reader.messages())
    except ReaderError as error:
        return f"{path} cannot be read: {error}"
    return None


def rosbag_says_indexed(path: Path) -> bool:
    """Debian's `rosbag info` reads the bag as indexed. (It calls a bag without messages,
    such as one of a run stopped before its first tick, not indexed whatever its index.)"""
    result = subprocess.run(
        [ROS_PYTHON, "/usr/bin/rosbag", "info", "--yaml", str(path)],
        capture_output=True,
        text=True,
        timeout=60,
        check=False,
    )
    if result.returncode != 0:
        return False
    info = yaml.safe_load(result.stdout)
    return info.get("indexed") is True or not info.get("messages")


def provide_replay_bag(data_root: Path, recorded: Path) -> None:
    shutil.copy(recorded, data_root / REPLAY_BAG)


@dataclass
class StopResult:
    plan: Plan
    seconds: float  # from the stop request to the end of the run (or process)
    status: int | None
    problem: str | None  # what went wrong, None: a good stop
    forced: bool = False  # ended by the forced exit (a second signal, or the deadline)


def summary(results: list[StopResult]) -> str:
    """Counts and the slowest stop, per kind and overall."""
    lines = []
    kinds = sorted({r.plan.stop for r in results}, key=lambda k: k.value)
    for kind in [*kinds, None]:
        chosen = [r for r in results if kind is None or r.plan.stop is kind]
        within = sum(r.seconds <= STOP_BOUND_S for r in chosen)
        times = sorted(r.seconds for r in chosen)
        median = times[len(times) // 2]
        lines.append(
            f"{'all' if kind is None else kind.value}: {len(chosen)} stops, {within} within "
            f"{STOP_BOUND_S:.0f} s, median {median * 1000:.0f} ms, slowest "
            f"{times[-1] * 1000:.0f} ms, {sum(r.forced for r in chosen)} forced, "
            f"{sum(r.problem is not None for r in chosen)} failed"
        )
    return "\n".join(lines)
