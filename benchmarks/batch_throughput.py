"""`egosim batch` throughput: cases per hour for the pure-pursuit lap suite, locally with
1, 2 (and 4) workers and on a local Ray instance.

Writes a suite of N cases (the example stack, sync clock, the first 50 m of the town lap,
seeds 1..N) to a temporary folder, exports morai_msgs for rospy there (`egosim msgs
--export-python` of each checkout, as its users would have them; Debian's ROS 1 needed),
runs `egosim batch` once per configuration and
reads results.json: wall time, cases per hour, and the split of a case's wall time
between the drive and the rest (starting the stack, joining the graph, stopping).

`--checkout DIR` (repeatable) runs the egosim source tree DIR instead of this one (its
`src` first on PYTHONPATH, with this venv's packages): to compare two versions, e.g.
before and after a change (`git worktree add --detach DIR main`). With several checkouts
and `--rounds`, the runs alternate checkout by checkout, so a shared machine's load falls
on each alike; every row gives the load average when it began.

CPU per case counts the processes the batch started (its driver, simulators and stacks;
not Ray's own workers and actors, which a Ray run does not start as its children). The
simulator and stack CPU columns are the medians of results.json's `simulator_cpu_s` and
`stack_cpu_s`, where the checkout records them.

Usage: .venv/bin/python benchmarks/batch_throughput.py [--cases 12] [--runs local1 local2 ray]
           [--checkout DIR ...] [--rounds 1] [--route-m 50]
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
RUNS = {
    "local1": ["--workers", "1"],
    "local2": ["--workers", "2"],
    "local4": ["--workers", "4"],
    "ray": ["--ray"],
}


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


def run_batch(suite: Path, out: Path, options: list[str], env: dict[str, str]) -> str:
    """One batch run; its table row."""
    load = os.getloadavg()[0]
    started = time.monotonic()
    cpu_before = _children_cpu_s()
    subprocess.run(
        [sys.executable, "-m", "egosim", "batch", str(suite), "--out", str(out), *options],
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
    return (
        f"{passed}/{len(cases)} | {load:.1f} | {batch_wall:.1f} (command {wall:.1f}) "
        f"| {len(cases) / batch_wall * 3600:.0f} | {statistics.mean(case_walls):.2f} "
        f"| {statistics.mean(drive_walls):.2f} | {cpu / len(cases):.2f} "
        f"| {_median_timing(cases, 'simulator_cpu_s')} | {_median_timing(cases, 'stack_cpu_s')} "
        f"| {sim_s:.2f} |"
    )


def _median_timing(cases: list[dict], key: str) -> str:
    """The median of a case timing (a worker's first case, which builds what the worker
    keeps, costs more), '-' where results.json has none."""
    values = [c["timings"].get(key) for c in cases]
    if None in values:
        return "-"
    return f"{statistics.median(values):.2f}"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", type=int, default=12)
    parser.add_argument(
        "--runs", nargs="+", choices=list(RUNS), default=["local1", "local2", "ray"]
    )
    parser.add_argument("--route-m", type=float, default=50.0, help="route length per case")
    parser.add_argument(
        "--checkout", type=Path, action="append", default=[], help="an egosim source tree"
    )
    parser.add_argument("--rounds", type=int, default=1)
    args = parser.parse_args()
    checkouts = [c.resolve() for c in args.checkout] or [ROOT]
    with tempfile.TemporaryDirectory() as temp:
        folder = Path(temp)
        environments = []
        for k, checkout in enumerate(checkouts):
            env = {n: v for n, v in os.environ.items() if not n.startswith("ROS_")}
            env["PYTHONPATH"] = str(checkout / "src")
            msgs = folder / f"msgs-{k}"
            subprocess.run(
                [sys.executable, "-m", "egosim", "msgs", "--export-python", str(msgs)],
                check=True,
                capture_output=True,
                env=env,
            )
            env["PYTHONPATH"] = os.pathsep.join([str(checkout / "src"), str(msgs)])
            environments.append(env)
        suite = write_suite(folder, args.cases, args.route_m)
        print(f"{args.cases} cases, {args.route_m:g} m routes")
        print(
            "| checkout | run | passed | load | wall (s) | cases/hour | case wall mean (s) "
            "| drive wall mean (s) | CPU per case (s) | simulator CPU (s) | stack CPU (s) "
            "| simulated per case (s) |"
        )
        print("|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
        for round_ in range(args.rounds):
            for run in args.runs:
                for k, checkout in enumerate(checkouts):
                    out = folder / f"{run}-{k}-{round_}"
                    row = run_batch(suite, out, RUNS[run], environments[k])
                    print(f"| {checkout.name} | {run} | {row}", flush=True)
        bag = next(folder.glob("*/*/drive.bag"))
        print(
            f"bag per case: {bag.stat().st_size / 1e6:.1f} MB; load after: {os.getloadavg()[0]:.1f}"
        )


if __name__ == "__main__":
    main()
