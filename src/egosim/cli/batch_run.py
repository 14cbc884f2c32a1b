"""`egosim batch` once its simulator workers have started (cli/batch.py starts them): the
suite loaded, its cases run, results.json, junit.xml and report.html written."""

from __future__ import annotations

import argparse
import fnmatch
import importlib
import importlib.util
import signal
import sys
import threading
import time
from collections.abc import Callable
from pathlib import Path

from ..app.exit_codes import EXIT_BAD_INPUT
from ..batch.case import CaseSpec
from ..batch.documents import Execution
from ..batch.early_workers import EarlyWorkers
from ..batch.errors import SuiteError
from ..batch.interrupt import EXIT_SIGNALLED, Interrupt, interrupted_by_signals
from ..batch.junit import write_junit
from ..batch.logs import tail_report
from ..batch.pool import Result, failed, run_local, run_ray
from ..batch.progress import BatchProgress
from ..batch.results import (
    needs_rerun,
    previous_results,
    results_document,
    summary,
    write_results,
)
from ..batch.suite import load_suite, scenario_suite
from ..scenario_files import is_morai_scenario, is_openscenario
from .arguments import LOCAL_RAY

EXIT_ALL_PASSED = 0
EXIT_SOME_FAILED = 1
REPORT_MODULE = "egosim.batch.html_report"
"""The HTML report's module: matplotlib and the maps, about 1 s of CPU to import."""


class ReportImports:
    """The report's imports, made in a thread of their own once no case is left to start
    and a slot is idle: that slot's core imports them while the last cases end, instead
    of the batch's start (whose cores the simulator workers' own imports keep busy) or
    its end."""

    def __init__(self) -> None:
        self._thread: threading.Thread | None = None

    def begin(self) -> None:
        if self._thread is None:
            self._thread = threading.Thread(
                target=importlib.import_module,
                args=(REPORT_MODULE,),
                name="report imports",
                daemon=True,
            )
            self._thread.start()

    def finish(self) -> None:
        """Once done (so that no import is left half made when the batch exits)."""
        if self._thread is not None:
            self._thread.join()


def selected(cases: list[CaseSpec], patterns: list[str]) -> list[CaseSpec]:
    if not patterns:
        return cases
    return [
        case
        for case in cases
        if any(case.name == p or fnmatch.fnmatchcase(case.name, p) for p in patterns)
    ]


def run_batch(args: argparse.Namespace, workers: int, early: EarlyWorkers) -> int:
    """The batch `args` ask for: its cases run by `workers` local slots, which take their
    simulator workers from `early`, or on Ray with --ray."""
    try:
        if is_openscenario(args.suite) or is_morai_scenario(args.suite):
            if not args.stack:
                print("egosim batch: a scenario file needs --stack COMMAND", file=sys.stderr)
                return EXIT_BAD_INPUT
            suite = scenario_suite(args.suite, args.stack, args.time_limit, args.clock)
        else:
            suite = load_suite(args.suite)
        cases = selected(suite, args.filter)
    except SuiteError as error:
        print(f"egosim batch: {error}", file=sys.stderr)
        return EXIT_BAD_INPUT
    out_dir = (args.out or Path("egosim-batch") / args.suite.stem).resolve()
    out_dir.mkdir(parents=True, exist_ok=True)
    results = previous_results(out_dir) if args.rerun_failed else {}
    to_run = [c for c in cases if needs_rerun(results.get(c.name))] if args.rerun_failed else cases
    if args.ray is not None and importlib.util.find_spec("ray") is None:
        print("egosim batch: --ray needs Ray: pip install 'egosim[ray]'", file=sys.stderr)
        return EXIT_BAD_INPUT
    interrupt = Interrupt()
    with interrupted_by_signals(interrupt) as reinstall:
        started = time.monotonic()
        report_imports = ReportImports()
        new = _run_cases(
            args, to_run, out_dir, workers, early, interrupt, reinstall, report_imports
        )
        report_imports.finish()
        return _report(args, cases, to_run, results, new, out_dir, workers, interrupt, started)


def _run_cases(
    args: argparse.Namespace,
    to_run: list[CaseSpec],
    out_dir: Path,
    workers: int,
    early: EarlyWorkers,
    interrupt: Interrupt,
    reinstall: Callable[[], None],
    report_imports: ReportImports,
) -> dict[str, Result]:
    done = failures = 0
    new: dict[str, Result] = {}
    with BatchProgress(len(to_run)) as bar:

        def on_result(result: Result, running: int) -> None:
            nonlocal done, failures
            done += 1
            failures += failed(result)
            if done + running == len(to_run) and running < workers:
                report_imports.begin()
            bar.log(f"{result['status'].upper():7} {result['name']}  {result.get('reason', '')}")
            for line in tail_report(result.get("log_tail")):
                bar.log(f"        {line}")
            bar.update(done, failures, running)

        if args.ray is not None:
            address = None if args.ray == LOCAL_RAY else args.ray
            run_ray(to_run, str(out_dir), address, on_result, new, interrupt, reinstall)
        else:
            run_local(to_run, str(out_dir), workers, on_result, new, interrupt, early)
    return new


def _report(
    args: argparse.Namespace,
    cases: list[CaseSpec],
    to_run: list[CaseSpec],
    results: dict[str, Result],
    new: dict[str, Result],
    out_dir: Path,
    workers: int,
    interrupt: Interrupt,
    started: float,
) -> int:
    results.update(new)
    execution: Execution = {
        "runner": "ray" if args.ray is not None else "local",
        "workers": None if args.ray is not None else workers,
        "cases_run": len(to_run),
        "wall_s": round(time.monotonic() - started, 3),
        "interrupted": interrupt.stop.is_set(),
    }
    document = results_document(args.suite, cases, results, execution)
    written = [write_results(out_dir, document), write_junit(out_dir, args.suite.stem, document)]
    if interrupt.hurry.is_set():
        print("egosim batch: stopped at once: no report.html", file=sys.stderr)
    else:
        from ..batch.html_report import write_html_report  # noqa: PLC0415 (ReportImports)

        written.append(write_html_report(out_dir, f"egosim batch: {args.suite.name}", document))
    counts = summary(document["cases"])
    print(", ".join(f"{v} {k}" for k, v in counts.items()), flush=True)
    for path in written:
        print(path, flush=True)
    if interrupt.stop.is_set():
        return EXIT_SIGNALLED + (interrupt.signal_number or signal.SIGINT)
    return EXIT_ALL_PASSED if counts["passed"] == counts["cases"] else EXIT_SOME_FAILED
