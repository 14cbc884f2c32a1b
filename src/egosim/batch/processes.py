"""A case's processes: each in its own session, stopped with its whole process group."""

from __future__ import annotations

import contextlib
import os
import signal
import subprocess
import sys
import time
from collections.abc import Callable, Sequence
from pathlib import Path

from egosim.batch.logs import BoundedLog

GRACE_S = 5.0
POLL_S = 0.05
DEFAULT_SIGNALS = Path(__file__).with_name("default_signals.py")


class GroupProcess:
    """A process started in a new session (its group is everything it starts) with the
    default signal handling (default_signals: whatever mask and ignored signals its parent
    has, SIGINT stops it gracefully) and whose output goes to a bounded log."""

    def __init__(
        self,
        args: Sequence[str],
        log_path: Path,
        env: dict[str, str] | None = None,
        cwd: Path | None = None,
        on_line: Callable[[str], None] | None = None,
    ) -> None:
        self.popen = subprocess.Popen(
            [sys.executable, "-I", "-S", str(DEFAULT_SIGNALS), *args],
            env=env,
            cwd=cwd,
            stdin=subprocess.DEVNULL,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            start_new_session=True,
        )
        assert self.popen.stdout is not None
        self.log = BoundedLog(self.popen.stdout, log_path, on_line)

    def poll(self) -> int | None:
        return self.popen.poll()

    def _group_alive(self) -> bool:
        try:
            os.killpg(self.popen.pid, 0)
        except ProcessLookupError:
            return False
        except PermissionError:
            return True
        return True

    def stop(self, first_signal: int = signal.SIGINT, grace_s: float = GRACE_S) -> int:
        """`first_signal` to the whole group, SIGKILL to what is left after `grace_s`;
        the exit status of the process itself."""
        with contextlib.suppress(ProcessLookupError):
            os.killpg(self.popen.pid, first_signal)
        deadline = time.monotonic() + grace_s
        while time.monotonic() < deadline:
            if self.popen.poll() is not None and not self._group_alive():
                break
            time.sleep(POLL_S)
        with contextlib.suppress(ProcessLookupError):
            os.killpg(self.popen.pid, signal.SIGKILL)
        status = self.popen.wait()
        self.log.join(GRACE_S)
        return status
