"""`egosim batch` throughput: cases per hour for the pure-pursuit lap suite, locally with
1 and 2 workers and as Ray tasks on a local Ray instance.

Writes a suite of N cases (the example stack, sync clock, the first 50 m of the town lap,
seeds 1..N) to a temporary folder, builds morai_msgs for rospy there (Debian's ROS 1
needed), runs `egosim batch` once per configuration and reads results.json: wall time,
cases per hour, and the split of a case's wall time between the drive and the rest
(starting the simulator and the stack, stopping them, writing the bag).

CPU per case counts the processes the batch started (not those of Ray's own workers,
which a Ray run does not start as its children).

Usage: .venv/bin/python benchmarks/batch_throughput.py [--cases 12] [--runs local1 local2 ray]
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"
MSGS = ROOT / "src" / "egosim" / "msgs" / "definitions" / "26.r1" / "morai_msgs"
BUILD_MSGS = ROOT / "tests" / "e2e" / "peers" / "build_msg_packages.py"
RUNS = {"local1": ["--workers", "1"], "local2": ["--workers", "2"], "ray": ["--ray"]}


def _children_cpu_s() -> float:
    """User + system CPU time of every finished child process so far (the batch, its
    cases' simulators and stacks; Ray's workers are not its children)."""
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def write_suite(folder: Path, cases: int, route_m: float) -> Path:
    suite = {
        "stack": {
            "command": f"/usr/bin/python3 {EXAMPLES / 'pure_pursuit_lap.py'} "
            f"{EXAMPLES / 'town_block_lap.csv'} --sync",
            "connect_timeout_s": 120,
        },
        "clock": "sync",
        "time_limit_s": 10,
        "criteria": ["no_collision", "route_completion >= 0.95"],
        "cases": [
            {
                "name": "lap",
                "scenario": str(EXAMPLES / "town_lap_scenario.yaml"),
                "route": {"csv": str(EXAMPLES / "town_block_lap.csv"), "first_m": route_m},
                "sweep": {"seed": list(range(1, cases + 1))},
            }
        ],
    }
    path = folder / "throughput.yaml"
    path.write_text(yaml.safe_dump(suite, sort_keys=False))
    return path


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", type=int, default=12)
    parser.add_argument("--runs", nargs="+", choices=list(RUNS), default=list(RUNS))
    parser.add_argument("--route-m", type=float, default=50.0, help="route length per case")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as temp:
        folder = Path(temp)
        subprocess.run(
            ["/usr/bin/python3", str(BUILD_MSGS), str(folder / "msgs"), str(MSGS)],
            check=True,
            capture_output=True,
        )
        suite = write_suite(folder, args.cases, args.route_m)
        env = {k: v for k, v in os.environ.items() if not k.startswith("ROS_")}
        env["PYTHONPATH"] = str(folder / "msgs")
        print(
            f"{args.cases} cases, {args.route_m:g} m routes, load before: {os.getloadavg()[0]:.1f}"
        )
        print(
            "| run | wall (s) | cases/hour | case wall mean (s) | drive wall mean (s) "
            "| CPU per case (s) | simulated per case (s) |"
        )
        print("|---|---:|---:|---:|---:|---:|---:|")
        for run in args.runs:
            out = folder / run
            started = time.monotonic()
            cpu_before = _children_cpu_s()
            subprocess.run(
                [sys.executable, "-m", "egosim", "batch", str(suite), "--out", str(out)]
                + RUNS[run],
                env=env,
                check=False,
                capture_output=True,
            )
            wall = time.monotonic() - started
            cpu = _children_cpu_s() - cpu_before
            document = json.loads((out / "results.json").read_text())
            cases = document["cases"]
            passed = document["summary"]["passed"]
            case_walls = [c["timings"]["case_wall_s"] for c in cases]
            drive_walls = [c["timings"]["drive_wall_s"] or 0.0 for c in cases]
            sim_s = statistics.mean(c["sim_time_s"] or 0.0 for c in cases)
            batch_wall = document["execution"]["wall_s"]
            print(
                f"| {run} ({passed}/{len(cases)} passed) | {batch_wall:.1f} (command {wall:.1f}) "
                f"| {len(cases) / batch_wall * 3600:.0f} | {statistics.mean(case_walls):.2f} "
                f"| {statistics.mean(drive_walls):.2f} | {cpu / len(cases):.2f} | {sim_s:.2f} |",
                flush=True,
            )
        bag = next(folder.glob("local1/*/drive.bag"), None) or next(folder.glob("*/*/drive.bag"))
        print(
            f"bag per case: {bag.stat().st_size / 1e6:.1f} MB; load after: {os.getloadavg()[0]:.1f}"
        )


if __name__ == "__main__":
    main()
