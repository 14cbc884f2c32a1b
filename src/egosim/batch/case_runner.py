"""Run one case: its ROS master here, its stack in its own process group and its simulator
in a warm worker (warm_simulator), supervised against deadlines; the case's result as
plain data. The same function serves the local pool and Ray actors.

The pool also runs the parts apart: `start_case` starts a case's master and stack before
its simulator is free (they wait for it, as a stack waits for any simulator to come up),
`drive_case` runs it on the simulator, and the EndingCase it returns gives the result
once the stack has ended, while the simulator already runs the next case. A case's
master is shut down only after its stack has ended: no stack ever reaches a master (or
a graph) of another case, whatever ports the system hands out.
"""

from __future__ import annotations

import json
import os
import re
import shutil
import signal
import threading
import time
from collections.abc import Callable
from pathlib import Path
from typing import Final, NamedTuple

from egosim.batch.case import CaseSpec
from egosim.batch.documents import CaseResult, CaseStatus, ScoreFile, read_score_file
from egosim.batch.files import BAG_FILE, CASE_FILE, SIMULATOR_LOG, STACK_LOG
from egosim.batch.interrupt import Interrupt
from egosim.batch.logs import log_tail
from egosim.batch.processes import GRACE_S, GroupProcess
from egosim.batch.ros_graph import CALLER_ID
from egosim.batch.warm_simulator import WarmSimulator
from egosim.batch.worker_protocol import ENDED, MASTER, PREFIX, RUNNING, SERVING
from egosim.evaluation import METRIC_NAMES, Metrics, parse_criterion
from egosim.ros1 import Master

# The simulator's last acts are closing the bag and writing the score; a loaded node may
# take seconds over them, and killing it before then loses both.
SIMULATOR_GRACE_S = 30.0

SIMULATOR_START_S = 60.0
POLL_S = 0.05
MASTER_URI = "http://127.0.0.1:0/"
"""Each case's master: loopback, on a port the system picks."""

PASSED: Final = "passed"
FAILED: Final = "failed"
ERROR: Final = "error"
"""A case passes its criteria, fails them, or could not be scored as asked (the stack
crashed, hung or never connected; the simulator failed)."""


class Problem(NamedTuple):
    """Why a case could not be scored as asked, and the log that tells more (None: no log
    does, e.g. the batch was interrupted)."""

    reason: str
    log: str | None = None


INTERRUPTED = Problem("interrupted")


def case_folder_name(name: str) -> str:
    """A file name for a case name (parameters keep their readable form)."""
    return re.sub(r"[^A-Za-z0-9_.,=\[\]-]", "_", name)


class _BatchStoppingError(Exception):
    """The batch is stopping: end the case now."""


class StartedCase:
    """A case's folder (case.json written), its ROS master (an empty graph and parameter
    server, /use_sim_time set) and its stack, started; its simulator not begun yet."""

    def __init__(self, case: CaseSpec, out_dir: str, ahead: bool) -> None:
        self.case = case
        self.ahead = ahead
        """Started ahead of its simulator (while the simulator ran another case)."""
        self.started = time.monotonic()
        self.folder = Path(out_dir) / case_folder_name(case.name)
        if self.folder.exists():
            shutil.rmtree(self.folder)
        self.folder.mkdir(parents=True)
        (self.folder / CASE_FILE).write_text(json.dumps(case.as_dict(), indent=1), encoding="utf-8")
        self.master = Master(MASTER_URI).start()
        # Set before the stack starts, so it always finds it (rospy reads it once, as its
        # node starts); the simulator sets it again.
        self.master.set_param(CALLER_ID, "/use_sim_time", True)
        # Until the simulator serves, the stack's lookups of its services wait for them.
        self.master.hold_lookups(True)
        self.stack = self._start_stack()

    def _start_stack(self) -> GroupProcess:
        case = self.case
        ros_home = self.folder / "ros"
        ros_home.mkdir(exist_ok=True)
        values = case.placeholders(str(self.folder))
        env = {k: v for k, v in os.environ.items() if not k.startswith("ROS_")}
        env.update({k: v.format_map(values) for k, v in case.stack.env.items()})
        env.update(
            ROS_MASTER_URI=self.master.uri,
            ROS_IP="127.0.0.1",
            ROS_HOME=str(ros_home),
            ROS_LOG_DIR=str(ros_home / "log"),
            PYTHONUNBUFFERED="1",
            EGOSIM_CASE=case.name,
            EGOSIM_CASE_DIR=str(self.folder),
        )
        for key in case.parameters:
            env[f"EGOSIM_PARAM_{key.upper()}"] = values[key]
        command = case.stack.command.format_map(values)
        return GroupProcess(
            ["/bin/sh", "-c", command], self.folder / STACK_LOG, env=env, cwd=self.folder
        )

    def discard(self, hurry: threading.Event | None = None) -> None:
        """Undo the start of a case that is not to run now: its stack stopped, its master
        shut down, its folder removed (nothing of it is left)."""
        self.stack.stop(signal.SIGINT, GRACE_S, hurry)
        self.master.shutdown()
        shutil.rmtree(self.folder, ignore_errors=True)


def start_case(case: CaseSpec, out_dir: str, ahead: bool = False) -> StartedCase:
    """Start `case`'s master and stack, its folder under `out_dir`; `ahead` of its
    simulator, or just before it."""
    return StartedCase(case, out_dir, ahead)


def run_case(
    case: CaseSpec,
    out_dir: str,
    simulator: WarmSimulator,
    interrupt: Interrupt | None = None,
) -> CaseResult:
    """Run `case` with its folder under `out_dir` on `simulator`; its result once its
    stack has ended too."""
    return drive_case(start_case(case, out_dir), simulator, interrupt).finish()


Watch = Callable[[float], None]
"""Called while a case drives, with the wall time since its drive began (s)."""


def drive_case(
    start: StartedCase,
    simulator: WarmSimulator,
    interrupt: Interrupt | None = None,
    watch: Watch | None = None,
) -> EndingCase:
    """Run the started case on `simulator` until the simulator is done with it: the
    simulator may take the next case while this one's stack ends (told to stop, it usually
    takes a fraction of a second: rospy's shutdown alone waits half a second for its
    threads). `watch` is called every POLL_S while the case drives."""
    supervisor = _Supervisor(start, simulator, interrupt or Interrupt(), watch)
    try:
        problem = supervisor.run()
    except _BatchStoppingError:
        problem = INTERRUPTED
    finally:
        supervisor.end_simulation()
    return EndingCase(supervisor, problem)


class EndingCase:
    """A case its simulator is done with, its stack perhaps still ending."""

    def __init__(self, supervisor: _Supervisor, problem: Problem | None) -> None:
        self._supervisor = supervisor
        self._problem = problem

    @property
    def drive_wall_s(self) -> float | None:
        """The drive's wall time as its supervisor saw it (None: it never began)."""
        return self._supervisor.drive_wall_s

    def finish(self) -> CaseResult:
        """The case's result, once its stack has ended (SIGKILL after its grace) and its
        master is shut down."""
        supervisor = self._supervisor
        case, folder = supervisor.case, supervisor.folder
        supervisor.stop_stack()
        supervisor.start.master.shutdown()
        drive = read_score_file(folder)
        result = _result(case, folder, self._problem, drive)
        if case.bags == "failed" and result["status"] == PASSED and result.get("bag") is not None:
            (folder / BAG_FILE).unlink()
            result["bag"] = None
        stack_cpu_s = supervisor.stack.cpu_s
        result["timings"] = {
            "case_wall_s": round(time.monotonic() - supervisor.start.started, 3),
            "drive_wall_s": None if drive is None else round(drive["drive_wall_s"], 3),
            "simulator_cpu_s": None if drive is None else round(drive["cpu_s"], 3),
            "stack_cpu_s": None if stack_cpu_s is None else round(stack_cpu_s, 3),
        }
        return result


class _Supervisor:
    def __init__(
        self,
        start: StartedCase,
        simulator: WarmSimulator,
        interrupt: Interrupt,
        watch: Watch | None,
    ) -> None:
        self.start = start
        self.case = start.case
        self.folder = start.folder
        self.stack = start.stack
        self.simulator = simulator
        self.interrupt = interrupt
        self.watch = watch
        self.stack_status: int | None = None
        self.drive_ended = False
        self.drive_wall_s: float | None = None

    def run(self) -> Problem | None:
        """Drive the case to its end; why it could not be scored, if it could not."""
        case = self.case
        self._check_interrupt()
        self.simulator.begin(self.folder, self.start.master.uri)
        if self._wait_for(MASTER, SIMULATOR_START_S) is None:
            return self._simulator_failure("did not start")
        running = self._wait_for(RUNNING, case.stack.connect_timeout_s, watch_stack=True)
        if running is None:
            if self.stack_status is not None:
                return _stack_problem(f"exited with status {self.stack_status} before connecting")
            if self.simulator.finished:
                return self._simulator_failure("stopped before the drive began")
            return _stack_problem(f"never connected within {case.stack.connect_timeout_s:g} s")
        return self._drive(started=time.monotonic())

    def _wait_for(self, what: str, timeout_s: float, watch_stack: bool = False) -> str | None:
        """The simulator's `egosim-batch: <what>` line, None if it did not come in time
        (or the simulator's case, or with `watch_stack` the stack, ended first)."""
        deadline = time.monotonic() + timeout_s
        while time.monotonic() < deadline:
            self._check_interrupt()
            line = self.simulator.take(POLL_S)
            if line == f"{PREFIX}{SERVING}":
                self.start.master.hold_lookups(False)
            if line is not None and line.startswith(f"{PREFIX}{what}"):
                return line
            if line is None:
                if self.simulator.finished:
                    return None
                if watch_stack and self._stack_ended():
                    return None
        return None

    def _stack_ended(self) -> bool:
        if self.stack_status is None:
            self.stack_status = self.stack.poll()
        return self.stack_status is not None

    def _drive(self, started: float) -> Problem | None:
        deadline = started + self.case.wall_limit_s
        while not self.simulator.finished:
            self._check_interrupt()
            if time.monotonic() > deadline:
                # A hung stack is the usual cause; its log says what it last did.
                reason = f"case exceeded its wall-clock limit of {self.case.wall_limit_s:g} s"
                return Problem(reason, STACK_LOG)
            line = self.simulator.take(POLL_S)
            if line is not None and line.startswith(f"{PREFIX}{ENDED}"):
                self.drive_ended = True
                self.drive_wall_s = time.monotonic() - started
            if self.watch is not None and not self.drive_ended:
                self.watch(time.monotonic() - started)
            if line is not None:
                continue
            if not self.drive_ended and self._stack_ended():
                # The drive ends with the stack; the simulator writes the score so far.
                # (A stack may fail once the drive is over: not the stack's fault.)
                self.simulator.stop_case(SIMULATOR_GRACE_S, self.interrupt.hurry)
                if self.stack_status != 0:
                    return _stack_problem(
                        f"exited with status {self.stack_status} during the drive"
                    )
                return None
        if self.simulator.status != 0:
            return self._simulator_failure(f"exited with status {self.simulator.status}")
        return None

    def _check_interrupt(self) -> None:
        if self.interrupt.stop.is_set():
            raise _BatchStoppingError

    def _simulator_failure(self, what: str) -> Problem:
        return Problem(f"simulator {what}", SIMULATOR_LOG)

    def end_simulation(self) -> None:
        """End the case's simulation: a stack still running is told to stop (SIGINT) and
        left to end while the simulator takes its next case (stop_stack waits for it) if
        its simulator is done with the case; otherwise it is stopped first (the simulator
        then writes what it saw), then the simulator's case."""
        self.start.master.hold_lookups(False)  # (a simulator that never served)
        if not self.simulator.finished:
            self.stop_stack()
        else:
            self.stack.begin_stop(signal.SIGINT)
        self.simulator.stop_case(SIMULATOR_GRACE_S, self.interrupt.hurry)

    def stop_stack(self) -> None:
        """Wait for the stack to end (SIGKILL to what is left after its grace, at once in
        a hurry)."""
        status = self.stack.stop(signal.SIGINT, GRACE_S, self.interrupt.hurry)
        if self.stack_status is None:
            self.stack_status = status


def _stack_problem(what: str) -> Problem:
    return Problem(f"stack {what}", STACK_LOG)


def _result(
    case: CaseSpec, folder: Path, problem: Problem | None, drive: ScoreFile | None
) -> CaseResult:
    score = None if drive is None else drive.get("score")
    outcome = None if drive is None else drive.get("scenario")
    if problem is None and drive is not None and drive["end"].startswith("bad route"):
        problem = Problem(drive["end"])
    if problem is None and score is None:
        problem = Problem("the drive was not scored (the simulator wrote no score)", SIMULATOR_LOG)
    checks = (
        []
        if score is None
        else [parse_criterion(c, METRIC_NAMES).check(score["metrics"]) for c in case.criteria]
    )
    failed = [c.text + (f" ({c.reason})" if c.reason else "") for c in checks if not c.passed]
    if outcome is not None and outcome.get("verdict") == "failure":
        failed.append("the scenario's evaluation failed")
    status: CaseStatus = ERROR if problem is not None else FAILED if failed else PASSED
    explained_by = None if problem is None else problem.log
    result: CaseResult = {
        "name": case.name,
        "parameters": case.parameters,
        "scenario": os.path.relpath(case.scenario_file, case.suite_dir),
        "folder": folder.name,
        "bag": f"{folder.name}/{BAG_FILE}" if (folder / BAG_FILE).exists() else None,
        "end": None if drive is None else drive["end"],
        "sim_time_s": None if drive is None else round(drive["sim_time_s"], 6),
        "metrics": None if score is None else _rounded(score["metrics"]),
        "infractions": None if score is None else score["infractions"],
        "criteria": [c.as_dict() for c in checks],
        "status": status,
        "reason": problem.reason if problem is not None else "; ".join(failed),
        "log_tail": None if explained_by is None else log_tail(folder, explained_by),
    }
    if outcome is not None:
        result["scenario_outcome"] = outcome
    return result


def _rounded(metrics: Metrics) -> Metrics:
    return {k: round(v, 6) if isinstance(v, float) else v for k, v in metrics.items()}
