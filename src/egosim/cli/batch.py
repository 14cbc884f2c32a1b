"""`egosim batch`: run a stack through a suite of scenario cases and report."""

from __future__ import annotations

import argparse
import fnmatch
import importlib.util
import signal
import sys
import time
from collections.abc import Callable
from pathlib import Path

from ..app.exit_codes import EXIT_BAD_INPUT
from ..batch.case import CaseSpec
from ..batch.documents import Execution
from ..batch.errors import SuiteError
from ..batch.html_report import write_html_report
from ..batch.interrupt import EXIT_SIGNALLED, Interrupt, interrupted_by_signals
from ..batch.junit import write_junit
from ..batch.logs import tail_report
from ..batch.pool import Result, default_workers, failed, run_local, run_ray
from ..batch.progress import BatchProgress
from ..batch.results import (
    needs_rerun,
    previous_results,
    results_document,
    summary,
    write_results,
)
from ..batch.suite import DEFAULT_TIME_LIMIT_S, load_suite, scenario_suite
from ..scenario_files import is_morai_scenario, is_openscenario

EXIT_ALL_PASSED = 0
EXIT_SOME_FAILED = 1
LOCAL_RAY = "local"


def positive_int(text: str) -> int:
    value = int(text)
    if value < 1:
        raise argparse.ArgumentTypeError(f"expected an integer >= 1, got {text}")
    return value


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.description = (
        "Run the suite's stack once per case, each case with its own ROS "
        "master and world on a simulator each worker keeps warm, score every drive from "
        "the world, and write results.json, junit.xml, report.html and a bag per case to "
        "the output folder. SIGINT or SIGTERM stops the running cases in order (their "
        "drives kept) and still writes every output; a second signal stops at once."
    )
    parser.add_argument(
        "suite",
        type=Path,
        metavar="SUITE.yaml|FILE.xosc|FILE.json",
        help="a suite file, or an OpenSCENARIO scenario or ParameterValueDistribution file "
        "(one case per concrete scenario), or a MORAI scenario file (one case); needs --stack",
    )
    parser.add_argument(
        "--stack",
        metavar="COMMAND",
        help="with a scenario file: the shell command that starts the stack",
    )
    parser.add_argument(
        "--time-limit",
        type=float,
        default=DEFAULT_TIME_LIMIT_S,
        metavar="SECONDS",
        help="with a scenario file: simulated time a case may take (default %(default)s)",
    )
    parser.add_argument(
        "--clock",
        choices=("sim", "sync"),
        default="sim",
        help="with a scenario file: sim (as fast as possible) or sync (the stack steps)",
    )
    parser.add_argument(
        "--workers",
        type=positive_int,
        default=None,
        metavar="N",
        help="cases at a time on this machine, each worker keeping a simulator warm "
        "(default: the number of cores)",
    )
    parser.add_argument(
        "--ray",
        nargs="?",
        const=LOCAL_RAY,
        default=None,
        metavar="ADDRESS",
        help="run the cases on Ray actors, one per CPU: of the cluster at ADDRESS, else of "
        "the one `ray start` runs here, else of a new local one (needs pip install "
        "egosim[ray])",
    )
    parser.add_argument(
        "--filter",
        action="append",
        default=[],
        metavar="GLOB",
        help="run only cases whose name matches (or equals) GLOB; repeatable",
    )
    parser.add_argument(
        "--rerun-failed",
        action="store_true",
        help="run only the cases that did not pass in the output folder's results.json",
    )
    parser.add_argument(
        "--out",
        type=Path,
        default=None,
        metavar="DIR",
        help="output folder (default: egosim-batch/<suite name>)",
    )
    parser.set_defaults(handler=run)


def selected(cases: list[CaseSpec], patterns: list[str]) -> list[CaseSpec]:
    if not patterns:
        return cases
    return [
        case
        for case in cases
        if any(case.name == p or fnmatch.fnmatchcase(case.name, p) for p in patterns)
    ]


def run(args: argparse.Namespace) -> int:
    if args.ray is not None and args.workers is not None:
        print("egosim batch: --workers is for local runs; Ray places the cases", file=sys.stderr)
        return EXIT_BAD_INPUT
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
    workers = args.workers or default_workers()
    interrupt = Interrupt()
    with interrupted_by_signals(interrupt) as reinstall:
        started = time.monotonic()
        new = _run_cases(args, to_run, out_dir, workers, interrupt, reinstall)
        return _report(args, cases, to_run, results, new, out_dir, workers, interrupt, started)


def _run_cases(
    args: argparse.Namespace,
    to_run: list[CaseSpec],
    out_dir: Path,
    workers: int,
    interrupt: Interrupt,
    reinstall: Callable[[], None],
) -> dict[str, Result]:
    done = failures = 0
    new: dict[str, Result] = {}
    with BatchProgress(len(to_run)) as bar:

        def on_result(result: Result, running: int) -> None:
            nonlocal done, failures
            done += 1
            failures += failed(result)
            bar.log(f"{result['status'].upper():7} {result['name']}  {result.get('reason', '')}")
            for line in tail_report(result.get("log_tail")):
                bar.log(f"        {line}")
            bar.update(done, failures, running)

        if args.ray is not None:
            address = None if args.ray == LOCAL_RAY else args.ray
            run_ray(to_run, str(out_dir), address, on_result, new, interrupt, reinstall)
        else:
            run_local(to_run, str(out_dir), workers, on_result, new, interrupt)
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
        written.append(write_html_report(out_dir, f"egosim batch: {args.suite.name}", document))
    counts = summary(document["cases"])
    print(", ".join(f"{v} {k}" for k, v in counts.items()), flush=True)
    for path in written:
        print(path, flush=True)
    if interrupt.stop.is_set():
        return EXIT_SIGNALLED + (interrupt.signal_number or signal.SIGINT)
    return EXIT_ALL_PASSED if counts["passed"] == counts["cases"] else EXIT_SOME_FAILED
