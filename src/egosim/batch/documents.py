"""The JSON a batch writes: score.json (a case's drive, from its simulator), each case's
result and results.json (docs/batch.md describes their keys)."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Literal, TypedDict

from egosim.batch.files import SCORE_FILE
from egosim.batch.logs import LogTail
from egosim.batch.sweep import Value
from egosim.evaluation import CriterionRecord, InfractionRecord, Metrics, ScoreRecord

CaseStatus = Literal["passed", "failed", "error", "not_run"]


class ScenarioOutcomeRecord(TypedDict):
    """A storyboard's end: its state, scenario time (s) and evaluation verdict."""

    state: str
    time_s: float
    verdict: str | None


class _Drive(TypedDict):
    end: str
    """route_completed, time_limit, blocked, stopped, "scenario <state>", "bad route: ..."."""
    sim_time_s: float
    drive_wall_s: float
    score: ScoreRecord | None
    """None: the drive never began."""


class Drive(_Drive, total=False):
    """What the drive stage saw."""

    scenario: ScenarioOutcomeRecord
    """Only for a scenario with a storyboard."""


class ScoreFile(Drive):
    """score.json: the drive, with the simulator's exit status and CPU time (s)."""

    exit_status: int
    cpu_s: float


def read_score_file(case_folder: Path) -> ScoreFile | None:
    """The case's score.json as its simulator wrote it; None if it wrote none."""
    try:
        drive: ScoreFile = json.loads((case_folder / SCORE_FILE).read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    return drive


class Timings(TypedDict):
    """Wall-clock and CPU figures of a case, s (they differ from run to run)."""

    case_wall_s: float
    drive_wall_s: float | None
    simulator_cpu_s: float | None
    stack_cpu_s: float | None


class _CaseVerdict(TypedDict):
    name: str
    parameters: dict[str, Value]
    status: CaseStatus
    reason: str


class CaseResult(_CaseVerdict, total=False):
    """One case in results.json. A case not run (or lost with its Ray task) has only the
    verdict's keys; a case that ran has the others, scenario_outcome only with a
    storyboard."""

    scenario: str
    folder: str
    bag: str | None
    end: str | None
    sim_time_s: float | None
    metrics: Metrics | None
    infractions: list[InfractionRecord] | None
    criteria: list[CriterionRecord]
    scenario_outcome: ScenarioOutcomeRecord
    log_tail: LogTail | None
    timings: Timings


class Summary(TypedDict):
    cases: int
    passed: int
    failed: int
    errors: int
    not_run: int


class Execution(TypedDict):
    """How the batch ran: the one part of results.json besides the timings that differs
    between two runs of a deterministic suite."""

    runner: Literal["local", "ray"]
    workers: int | None
    """None on Ray (its actors place the cases)."""
    cases_run: int
    wall_s: float
    interrupted: bool


class ResultsDocument(TypedDict):
    """results.json."""

    suite: str
    egosim_version: str
    summary: Summary
    cases: list[CaseResult]
    execution: Execution
