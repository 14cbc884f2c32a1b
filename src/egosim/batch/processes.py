"""A case's processes: each in its own session, stopped with its whole process group."""

from __future__ import annotations

import contextlib
import os
import signal
import subprocess
import sys
import threading
import time
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import IO, Protocol

from egosim.batch.logs import BoundedLog

GRACE_S = 5.0
POLL_S = 0.05
DEFAULT_SIGNALS = Path(__file__).with_name("default_signals.py")


class OutputReader(Protocol):
    """What reads a process's output (stdout and stderr, merged) in a thread of its own."""

    def join(self, timeout_s: float) -> None: ...


class GroupProcess:
    """A process started in a new session (its group is everything it starts) with the
    default signal handling (default_signals: whatever mask and ignored signals its parent
    has, SIGINT stops it gracefully) and whose output goes to a bounded log (`log`: its
    path), or to the reader `log` makes of it. With `commands` its standard input is a
    pipe (`self.popen.stdin`), else empty."""

    def __init__(
        self,
        args: Sequence[str],
        log: Path | Callable[[IO[bytes]], OutputReader],
        env: dict[str, str] | None = None,
        cwd: Path | None = None,
        on_line: Callable[[str], None] | None = None,
        commands: bool = False,
    ) -> None:
        self.started = time.monotonic()
        self.popen = subprocess.Popen(
            [sys.executable, "-I", "-S", str(DEFAULT_SIGNALS), *args],
            env=env,
            cwd=cwd,
            stdin=subprocess.PIPE if commands else subprocess.DEVNULL,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            start_new_session=True,
        )
        assert self.popen.stdout is not None
        stdout = self.popen.stdout
        self.log = BoundedLog(stdout, log, on_line) if isinstance(log, Path) else log(stdout)
        self.cpu_s: float | None = None
        """User + system CPU time of the process and what it waited for, once it ended."""
        self._reaping = threading.Lock()
        self._stopping_since: float | None = None

    def poll(self) -> int | None:
        return self._reap(os.WNOHANG)

    def wait(self) -> int:
        status = self._reap(0)
        assert status is not None
        return status

    def _reap(self, options: int) -> int | None:
        """The exit status once the process has ended (with its CPU time: os.wait4, not
        Popen's own wait, which drops it)."""
        with self._reaping:
            if self.popen.returncode is None:
                pid, status, usage = os.wait4(self.popen.pid, options)
                if pid != 0:
                    self.popen.returncode = os.waitstatus_to_exitcode(status)
                    self.cpu_s = usage.ru_utime + usage.ru_stime
            return self.popen.returncode

    def _group_alive(self) -> bool:
        try:
            os.killpg(self.popen.pid, 0)
        except ProcessLookupError:
            return False
        except PermissionError:
            return True
        return True

    def begin_stop(self, first_signal: int = signal.SIGINT) -> None:
        """`first_signal` to the whole group, once: the grace of `stop` runs from now."""
        if self._stopping_since is None:
            self._stopping_since = time.monotonic()
            with contextlib.suppress(ProcessLookupError):
                os.killpg(self.popen.pid, first_signal)

    def stop(
        self,
        first_signal: int = signal.SIGINT,
        grace_s: float = GRACE_S,
        hurry: threading.Event | None = None,
    ) -> int:
        """`first_signal` to the whole group (unless `begin_stop` sent it already),
        SIGKILL to what is left `grace_s` after it (at once when `hurry` is set); the exit
        status of the process itself."""
        self.begin_stop(first_signal)
        assert self._stopping_since is not None
        self.wait_group(max(self._stopping_since + grace_s - time.monotonic(), 0.0), hurry)
        return self.kill()

    def wait_group(self, timeout_s: float, hurry: threading.Event | None = None) -> bool:
        """Wait up to `timeout_s` (less if `hurry` is set) for the process and everything
        in its group to end; whether they did."""
        hurry = hurry or threading.Event()
        deadline = time.monotonic() + timeout_s
        while not (self.poll() is not None and not self._group_alive()):
            if time.monotonic() >= deadline or hurry.wait(POLL_S):
                return False
        return True

    def kill(self) -> int:
        """SIGKILL to whatever is left of the group; the exit status of the process."""
        with contextlib.suppress(ProcessLookupError):
            os.killpg(self.popen.pid, signal.SIGKILL)
        status = self.wait()
        self.log.join(GRACE_S)
        return status
