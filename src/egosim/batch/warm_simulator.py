"""The supervisor's side of a simulator worker: one warm process (`python -m
egosim.batch.worker`) that runs one case after another for a worker slot of the batch (a
thread of the local pool, a Ray actor), started ahead of its cases (early_workers) or when
its first case begins, and again whenever the last one left it gone or replaced.

Its output goes to the simulator.log of the case it belongs to (the worker says where
each case begins and ends); its protocol lines (worker_protocol) are handed to the case's
supervisor in order.
"""

from __future__ import annotations

import contextlib
import logging
import os
import queue
import sys
import threading
import time
from pathlib import Path
from typing import IO

from egosim.batch.files import SIMULATOR_LOG
from egosim.batch.logs import BoundedFile
from egosim.batch.processes import POLL_S, GroupProcess
from egosim.batch.worker_protocol import (
    DONE,
    PREFIX,
    Done,
    case_dir_of,
    done_of,
    run_command,
    stop_command,
)

log = logging.getLogger(__name__)

CLOSE_GRACE_S = 30.0
"""An idle worker exits at once when told; one still in a case first ends it."""
EXITED = object()
"""Queued after the worker's last line once it has exited."""


class WarmSimulator:
    def __init__(self) -> None:
        self._process: GroupProcess | None = None
        self._lines: queue.Queue[str | object] = queue.Queue()
        self._logs: _CaseLogs
        self._done: Done | None = None
        self._exit_status: int | None = None
        self._in_case = False

    # The case's side ------------------------------------------------------------------

    def begin(self, folder: Path, master_uri: str) -> None:
        """Run the case in `folder` (its case.json written) on the master at `master_uri`."""
        if self._process is not None and (self._last_done() or self._process.poll() is not None):
            self._end_process(CLOSE_GRACE_S)
        if self._process is None:
            self.start()
        self._done = None
        self._in_case = True
        self._logs.pending = folder
        command = run_command(folder, master_uri)
        if not self._send(command):
            self._end_process(0.0)
            self.start()
            self._logs.pending = folder
            self._send(command)

    def take(self, wait_s: float = 0.0) -> str | None:
        """The case's next protocol line (None if none came within `wait_s`); after its
        `done` line, or the worker's exit, `finished` holds."""
        try:
            line = self._lines.get(timeout=wait_s) if wait_s > 0 else self._lines.get_nowait()
        except queue.Empty:
            return None
        if line is EXITED:
            assert self._process is not None
            self._exit_status = self._process.wait()
            self._in_case = False
            return None
        assert isinstance(line, str)
        if (done := done_of(line)) is not None:
            self._done = done
            self._in_case = False
        return line

    @property
    def finished(self) -> bool:
        return not self._in_case

    @property
    def status(self) -> int | None:
        """The case's run's exit status (the worker's own when it died in the case)."""
        return self._done.status if self._done is not None else self._exit_status

    def stop_case(self, grace_s: float, hurry: threading.Event | None = None) -> None:
        """End the case now (the simulator writes the score so far); the worker is killed
        if it has not ended it within `grace_s` (at once with `hurry` set)."""
        if self.finished:
            return
        hurry = hurry or threading.Event()
        if not hurry.is_set():
            self._send(stop_command())
        deadline = time.monotonic() + grace_s
        while not self.finished:
            if self.take(POLL_S) is not None:
                continue
            if hurry.is_set() or time.monotonic() >= deadline:
                self._kill()
                return

    # The slot's side ------------------------------------------------------------------

    def close(self, hurry: threading.Event | None = None) -> None:
        """End the worker (its case too, if one still runs): no process is left."""
        if self._process is not None:
            self._end_process(0.0 if hurry is not None and hurry.is_set() else CLOSE_GRACE_S)

    def discard(self) -> None:
        """End a worker that was handed no case, at once: it has nothing to finish."""
        assert self.finished
        process, self._process = self._process, None
        if process is not None:
            assert process.popen.stdin is not None
            with contextlib.suppress(BrokenPipeError):
                process.popen.stdin.close()
            process.kill()

    def start(self) -> None:
        """Start the worker now (its first case would): it imports egosim, numpy, numba
        and rosbags meanwhile, ready for the case to begin."""
        env = {k: v for k, v in os.environ.items() if not k.startswith("ROS_")}
        env["PYTHONUNBUFFERED"] = "1"
        self._lines = queue.Queue()
        self._exit_status = None
        self._process = GroupProcess(
            [sys.executable, "-m", "egosim.batch.worker"],
            self._logs_of,
            env=env,
            commands=True,
        )

    def _logs_of(self, stream: IO[bytes]) -> _CaseLogs:
        self._logs = _CaseLogs(stream, self._lines)
        return self._logs

    def _send(self, command: bytes) -> bool:
        assert self._process is not None and self._process.popen.stdin is not None
        try:
            self._process.popen.stdin.write(command)
            self._process.popen.stdin.flush()
        except (BrokenPipeError, ValueError):  # it has exited (or was closed)
            return False
        return True

    def _last_done(self) -> bool:
        return self._done is not None and self._done.last

    def _kill(self) -> None:
        assert self._process is not None
        self._process.kill()
        while not self.finished:
            self.take(POLL_S)

    def _end_process(self, grace_s: float) -> None:
        """Close the worker's input (it ends its case, if any, and exits), SIGKILL its
        group after `grace_s`; the lines it still had for its case are dropped."""
        process, self._process = self._process, None
        assert process is not None and process.popen.stdin is not None
        with contextlib.suppress(BrokenPipeError):
            process.popen.stdin.close()
        if not process.wait_group(grace_s):
            log.warning(
                "simulator worker %d did not exit within %g s: killed", process.popen.pid, grace_s
            )
        process.kill()
        self._in_case = False


class _CaseLogs:
    """Reads the worker's output in a thread: each case's part to that case's
    simulator.log, its protocol lines also to `lines`. What comes before a case's first
    line belongs to the case the worker was handed (`pending`: a worker that fails to
    start says why there); output between cases (there should be none) goes to this
    process's log."""

    def __init__(self, stream: IO[bytes], lines: queue.Queue[str | object]) -> None:
        self._stream = stream
        self._lines = lines
        self.pending: Path | None = None
        self._thread = threading.Thread(target=self._copy, name="simulator worker", daemon=True)
        self._thread.start()

    def _copy(self) -> None:
        current: BoundedFile | None = None
        try:
            for raw in self._stream:
                text = raw.decode("utf-8", "replace").rstrip("\n")
                if (folder := case_dir_of(text)) is not None:
                    self.pending = None
                    if current is None or current.path != folder / SIMULATOR_LOG:
                        if current is not None:
                            current.close()
                        current = BoundedFile(folder / SIMULATOR_LOG)
                    continue
                if current is None and self.pending is not None:
                    current = BoundedFile(self.pending / SIMULATOR_LOG)
                if current is None:
                    log.warning("simulator worker: %s", text)
                    continue
                current.write(raw)
                if text.startswith(PREFIX):
                    if text.startswith(f"{PREFIX}{DONE} "):
                        current.close()
                        current = None
                    self._lines.put(text)
        finally:
            if current is not None:
                current.close()
            self._stream.close()
            self._lines.put(EXITED)

    def join(self, timeout_s: float) -> None:
        self._thread.join(timeout_s)
