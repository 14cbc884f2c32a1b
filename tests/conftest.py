"""Shared fixtures for tests that run Debian's real ROS 1 next to egosim.

- ``ros_env``: environment for ROS subprocesses (ROS_HOME/ROS_LOG_DIR in a tmp dir).
- ``spawn_ros``: start a subprocess in its own process group; killed at teardown.
  (``ros_environment`` and ``ros_spawner`` are the same for fixtures of a wider scope.)
- ``rosmaster``: Debian's rosmaster on a free loopback port; yields its URI.
- ``embedded_master``: egosim's master on a free loopback port; yields it (``.uri``).
- ``built_msg_packages``: morai_msgs as rospy modules (`egosim msgs --export-python`).
Tests marked ``ros`` are skipped, with the reason, when Debian's ROS 1 is not installed.
"""

from __future__ import annotations

import contextlib
import os
import queue
import re
import signal
import socket
import subprocess
import sys
import threading
import time
import xmlrpc.client
from collections.abc import Callable, Iterator
from pathlib import Path

import pytest

from egosim.ros1 import Master
from tests.debian_ros import ROS_PYTHON, missing_ros_reason, require_ros

#: Generous bound on waiting for a peer's event (never a timed assertion).
EVENT_TIMEOUT_S = 30.0


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    reason = missing_ros_reason()
    if reason is None:
        return
    for item in items:
        if item.get_closest_marker("ros") or item.get_closest_marker("roscpp"):
            item.add_marker(pytest.mark.skip(reason=reason))


def free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


class RosProcess:
    """A subprocess whose stdout lines can be awaited; stderr goes to a log file."""

    def __init__(self, args: list[str], env: dict[str, str], log_path: Path) -> None:
        self.args = args
        self.log_path = log_path
        self._stderr = log_path.open("wb")
        self.popen = subprocess.Popen(
            args,
            env=env,
            stdin=subprocess.DEVNULL,
            stdout=subprocess.PIPE,
            stderr=self._stderr,
            start_new_session=True,
            text=True,
        )
        self.lines: queue.Queue[str] = queue.Queue()
        self.output: list[str] = []
        self._reader = threading.Thread(target=self._read, daemon=True)
        self._reader.start()

    def _read(self) -> None:
        assert self.popen.stdout is not None
        for line in self.popen.stdout:
            self.lines.put(line.rstrip("\n"))

    def expect(self, pattern: str, timeout: float = EVENT_TIMEOUT_S) -> re.Match[str]:
        """The first new stdout line matching ``pattern``; fails with the output so far."""
        deadline = time.monotonic() + timeout
        while True:
            remaining = deadline - time.monotonic()
            try:
                line = self.lines.get(timeout=max(remaining, 0.01))
            except queue.Empty:
                pytest.fail(
                    f"{self.args[:3]} printed no line matching {pattern!r}; stdout: "
                    f"{self.output[-20:]}; stderr: {self.stderr_text()[-3000:]}"
                )
            self.output.append(line)
            if match := re.search(pattern, line):
                return match

    def wait(self, timeout: float = EVENT_TIMEOUT_S) -> int:
        return self.popen.wait(timeout)

    def stderr_text(self) -> str:
        self._stderr.flush()
        return self.log_path.read_text(errors="replace")

    def _group_alive(self) -> bool:
        try:
            os.killpg(self.popen.pid, 0)
        except ProcessLookupError:
            return False
        return True

    def kill(self) -> None:
        """SIGINT to the whole process group (so e.g. rosbag's recorder closes its bag), then
        SIGKILL to whatever is left of it after a grace period."""
        with contextlib.suppress(ProcessLookupError):
            os.killpg(self.popen.pid, signal.SIGINT)
        deadline = time.monotonic() + 10
        while time.monotonic() < deadline:
            with contextlib.suppress(subprocess.TimeoutExpired):
                self.popen.wait(0.05)
            if self.popen.poll() is not None:
                if not self._group_alive():
                    break
                time.sleep(0.05)  # the leader is gone, the rest of its group not yet
        with contextlib.suppress(ProcessLookupError):
            os.killpg(self.popen.pid, signal.SIGKILL)
        self.popen.wait()
        self._stderr.close()
        # The reader sees end-of-file once the whole process group is gone.
        self._reader.join(EVENT_TIMEOUT_S)
        if self.popen.stdout is not None:
            self.popen.stdout.close()


def ros_environment(directory: Path) -> dict[str, str]:
    """The environment of ROS subprocesses, their ROS_HOME and logs in `directory`."""
    env = {k: v for k, v in os.environ.items() if not k.startswith("ROS_")}
    home = directory / "ros_home"
    home.mkdir(exist_ok=True)
    env.update(ROS_HOME=str(home), ROS_LOG_DIR=str(home / "log"), PYTHONUNBUFFERED="1")
    env.pop("PYTHONPATH", None)
    return env


@contextlib.contextmanager
def ros_spawner(directory: Path, ros_env: dict[str, str]) -> Iterator[Callable[..., RosProcess]]:
    """``spawn(args, master_uri=None, **env)`` starts a process (stderr in `directory`),
    each killed on leaving; ``args[0] == "python"`` means Debian's ROS interpreter."""
    started: list[RosProcess] = []

    def spawn(args: list[str], master_uri: str | None = None, **extra_env: str) -> RosProcess:
        env = dict(ros_env, **extra_env)
        if master_uri is not None:
            env["ROS_MASTER_URI"] = master_uri
        if args[0] == "python":
            args = [ROS_PYTHON, *args[1:]]
        process = RosProcess(args, env, directory / f"proc{len(started)}.stderr")
        started.append(process)
        return process

    try:
        yield spawn
    finally:
        for process in reversed(started):
            process.kill()


@pytest.fixture
def ros_env(tmp_path: Path) -> dict[str, str]:
    return ros_environment(tmp_path)


@pytest.fixture
def spawn_ros(tmp_path: Path, ros_env: dict[str, str]) -> Iterator[Callable[..., RosProcess]]:
    """``spawn_ros(args, master_uri=None, **env)``: ros_spawner for the test."""
    with ros_spawner(tmp_path, ros_env) as spawn:
        yield spawn


def wait_for_master(uri: str, timeout: float = EVENT_TIMEOUT_S) -> None:
    deadline = time.monotonic() + timeout
    while True:
        try:
            xmlrpc.client.ServerProxy(uri).getUri("/test")
            return
        except OSError:
            if time.monotonic() > deadline:
                pytest.fail(f"no master answered at {uri}")
            time.sleep(0.05)


@pytest.fixture
def rosmaster(spawn_ros: Callable[..., RosProcess]) -> str:
    """Debian's rosmaster on a free loopback port; its URI."""
    if reason := missing_ros_reason():
        pytest.skip(reason)
    port = free_port()
    uri = f"http://127.0.0.1:{port}/"
    spawn_ros(["/usr/bin/rosmaster", "--core", "-p", str(port)], ROS_IP="127.0.0.1")
    wait_for_master(uri)
    return uri


@pytest.fixture
def embedded_master() -> Iterator[Master]:
    """egosim's embedded master on a free loopback port."""
    master = Master(f"http://127.0.0.1:{free_port()}/").start()
    try:
        yield master
    finally:
        master.shutdown()


@pytest.fixture(scope="session")
def built_msg_packages(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """morai_msgs (26.r1) and its dependencies as rospy modules, written by
    `egosim msgs --export-python` with Debian's genpy; put it on PYTHONPATH."""
    require_ros()
    outdir = tmp_path_factory.mktemp("msg_packages")
    subprocess.run(
        [sys.executable, "-m", "egosim", "msgs", "--export-python", str(outdir)],
        check=True,
        capture_output=True,
        timeout=300,
    )
    return outdir
