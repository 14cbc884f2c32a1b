"""Run one case: its stack in its own process group and its simulator in a warm worker
(warm_simulator), supervised against deadlines; the case's result as plain data. The same
function serves the local pool and Ray actors."""

from __future__ import annotations

import json
import os
import re
import shutil
import signal
import time
from pathlib import Path
from typing import Final, NamedTuple
from urllib.parse import urlsplit

from egosim.batch.case import CaseSpec
from egosim.batch.documents import CaseResult, CaseStatus, ScoreFile, read_score_file
from egosim.batch.files import BAG_FILE, CASE_FILE, SIMULATOR_LOG, STACK_LOG
from egosim.batch.interrupt import Interrupt
from egosim.batch.live_masters import LiveMasters
from egosim.batch.logs import log_tail
from egosim.batch.processes import GRACE_S, GroupProcess
from egosim.batch.warm_simulator import WarmSimulator
from egosim.batch.worker_protocol import ENDED, MASTER, MASTER_LINE, PREFIX, RUNNING
from egosim.evaluation import METRIC_NAMES, Metrics, parse_criterion

# The simulator's last acts are closing the bag and writing the score; a loaded node may
# take seconds over them, and killing it before then loses both.
SIMULATOR_GRACE_S = 30.0

SIMULATOR_START_S = 60.0
POLL_S = 0.05

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


def run_case(
    case: CaseSpec,
    out_dir: str,
    simulator: WarmSimulator,
    interrupt: Interrupt | None = None,
) -> CaseResult:
    """Run `case` with its folder under `out_dir` on `simulator`; its result once its
    stack has ended too."""
    return drive_case(case, out_dir, simulator, interrupt).finish()


def drive_case(
    case: CaseSpec,
    out_dir: str,
    simulator: WarmSimulator,
    interrupt: Interrupt | None = None,
    masters: LiveMasters | None = None,
) -> EndingCase:
    """Run `case` with its folder under `out_dir` on `simulator` until the simulator is
    done with it: `simulator` may take the next case while this one's stack ends (told
    to stop, it usually takes a fraction of a second: rospy's shutdown alone waits half
    a second for its threads). `masters` holds the ports of the masters that stacks of
    this batch may still reach; this case's master takes none of them."""
    started = time.monotonic()
    folder = Path(out_dir) / case_folder_name(case.name)
    if folder.exists():
        shutil.rmtree(folder)
    folder.mkdir(parents=True)
    (folder / CASE_FILE).write_text(json.dumps(case.as_dict(), indent=1), encoding="utf-8")
    supervisor = _Supervisor(case, folder, simulator, interrupt or Interrupt(), masters)
    try:
        problem = supervisor.run()
    except _BatchStoppingError:
        problem = INTERRUPTED
    finally:
        supervisor.end_simulation()
    return EndingCase(supervisor, problem, started)


class EndingCase:
    """A case its simulator is done with, its stack perhaps still ending."""

    def __init__(self, supervisor: _Supervisor, problem: Problem | None, started: float) -> None:
        self._supervisor = supervisor
        self._problem = problem
        self._started = started

    def finish(self) -> CaseResult:
        """The case's result, once its stack has ended (SIGKILL after its grace)."""
        supervisor, case, folder = self._supervisor, self._supervisor.case, self._supervisor.folder
        supervisor.stop_stack()
        drive = read_score_file(folder)
        result = _result(case, folder, self._problem, drive)
        if case.bags == "failed" and result["status"] == PASSED and result.get("bag") is not None:
            (folder / BAG_FILE).unlink()
            result["bag"] = None
        stack_cpu_s = None if supervisor.stack is None else supervisor.stack.cpu_s
        result["timings"] = {
            "case_wall_s": round(time.monotonic() - self._started, 3),
            "drive_wall_s": None if drive is None else round(drive["drive_wall_s"], 3),
            "simulator_cpu_s": None if drive is None else round(drive["cpu_s"], 3),
            "stack_cpu_s": None if stack_cpu_s is None else round(stack_cpu_s, 3),
        }
        return result


class _Supervisor:
    def __init__(
        self,
        case: CaseSpec,
        folder: Path,
        simulator: WarmSimulator,
        interrupt: Interrupt,
        masters: LiveMasters | None,
    ) -> None:
        self.case = case
        self.folder = folder
        self.simulator = simulator
        self.interrupt = interrupt
        self.masters = masters or LiveMasters()
        self.master_port: int | None = None
        self.stack: GroupProcess | None = None
        self.stack_status: int | None = None
        self.drive_ended = False

    def run(self) -> Problem | None:
        """Drive the case to its end; why it could not be scored, if it could not."""
        case = self.case
        self._check_interrupt()
        self.simulator.begin(self.folder, self.masters.ports())
        master = self._wait_for(MASTER, SIMULATOR_START_S)
        if master is None:
            return self._simulator_failure("did not start its ROS master")
        uri = MASTER_LINE.match(master).group(1)  # type: ignore[union-attr]
        self.master_port = urlsplit(uri).port
        if self.master_port is not None:
            self.masters.add(self.master_port)
        self.stack = self._start_stack(uri)
        running = self._wait_for(RUNNING, case.stack.connect_timeout_s, watch_stack=True)
        if running is None:
            if self.stack_status is not None:
                return _stack_problem(f"exited with status {self.stack_status} before connecting")
            if self.simulator.finished:
                return self._simulator_failure("stopped before the drive began")
            return _stack_problem(f"never connected within {case.stack.connect_timeout_s:g} s")
        return self._drive(started=time.monotonic())

    def _start_stack(self, master_uri: str) -> GroupProcess:
        case = self.case
        ros_home = self.folder / "ros"
        ros_home.mkdir(exist_ok=True)
        values = case.placeholders(str(self.folder))
        env = {k: v for k, v in os.environ.items() if not k.startswith("ROS_")}
        env.update({k: v.format_map(values) for k, v in case.stack.env.items()})
        env.update(
            ROS_MASTER_URI=master_uri,
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

    def _wait_for(self, what: str, timeout_s: float, watch_stack: bool = False) -> str | None:
        """The simulator's `egosim-batch: <what>` line, None if it did not come in time
        (or the simulator's case, or with `watch_stack` the stack, ended first)."""
        deadline = time.monotonic() + timeout_s
        while time.monotonic() < deadline:
            self._check_interrupt()
            line = self.simulator.take(POLL_S)
            if line is not None and line.startswith(f"{PREFIX}{what}"):
                return line
            if line is None:
                if self.simulator.finished:
                    return None
                if watch_stack and self._stack_ended():
                    return None
        return None

    def _stack_ended(self) -> bool:
        if self.stack is not None and self.stack_status is None:
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
            self.drive_ended |= line is not None and line.startswith(f"{PREFIX}{ENDED}")
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
        if self.stack is not None and not self.simulator.finished:
            self.stop_stack()
        elif self.stack is not None:
            self.stack.begin_stop(signal.SIGINT)
        self.simulator.stop_case(SIMULATOR_GRACE_S, self.interrupt.hurry)

    def stop_stack(self) -> None:
        """Wait for the stack to end (SIGKILL to what is left after its grace, at once in
        a hurry); its master's port may then go to another case's master."""
        if self.stack is not None:
            status = self.stack.stop(signal.SIGINT, GRACE_S, self.interrupt.hurry)
            if self.stack_status is None:
                self.stack_status = status
        if self.master_port is not None:
            self.masters.remove(self.master_port)
            self.master_port = None


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
