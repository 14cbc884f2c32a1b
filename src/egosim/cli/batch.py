"""`egosim batch`: run a stack through a suite of scenario cases and report. Its options,
and its start: a local batch's simulator workers first (early_workers), then the rest
(batch_run)."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from ..app.exit_codes import EXIT_BAD_INPUT
from ..batch.case import DEFAULT_TIME_LIMIT_S
from ..batch.early_workers import EarlyWorkers, default_workers
from .arguments import LOCAL_RAY


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


def run(args: argparse.Namespace) -> int:
    if args.ray is not None and args.workers is not None:
        print("egosim batch: --workers is for local runs; Ray places the cases", file=sys.stderr)
        return EXIT_BAD_INPUT
    workers = args.workers or default_workers()
    with EarlyWorkers(0 if args.ray is not None else workers) as early:
        # Imported once the workers have started: they import (0.9 s) beside the driver.
        from .batch_run import run_batch  # noqa: PLC0415

        return run_batch(args, workers, early)
