"""Where a batch case's fixed cost goes: the CPU time (user + system) of each part of
starting a case's simulator, the first time in a process (a case in a process of its own)
and again in the same process (a warm simulator worker's next case), and of what the
stack's side imports.

The simulator's parts are those of `egosim.batch.simulate` on the town with the example's
scenario, sync clock, every row: importing egosim (in a new interpreter, per run), the
master, the world (map and scenario), the ROS node (the message types), the simulation
context (sensors, the camera rig: renderer and scene), registering every topic and
service, and shutting down; and a whole new interpreter importing it. The stack's:
`/usr/bin/python3 -c 'import rospy, morai_msgs.msg, morai_msgs.srv'` with the exported
messages on its path (Debian's ROS 1 needed; skipped without it).

Usage: .venv/bin/python benchmarks/case_startup.py [--runs 3]
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SCENARIO = ROOT / "examples" / "town_lap_scenario.yaml"

PARTS = """
import os, resource, sys, time
from pathlib import Path

def cpu():
    usage = resource.getrusage(resource.RUSAGE_SELF)
    return usage.ru_utime + usage.ru_stime

mark = cpu()
def part(name):
    global mark
    now = cpu()
    print(f"{name} {now - mark:.4f}", flush=True)
    mark = now

import egosim.batch.simulate
from egosim.app.inbox import Inbox
from egosim.app.options import RunOptions
from egosim.app.runner import build_world
from egosim.bridge import HANDLERS, Bridge, ClockMode, simulation_context
from egosim.bridge.protocol.network import load_network_settings
from egosim.render import open_renderer
from egosim.ros1 import Master, Node
part("import")
renderer = None
def shared():
    global renderer
    renderer = renderer or open_renderer()
    return renderer
for case in ("first", "next"):
    print(case, flush=True)
    master = Master("http://127.0.0.1:0/").start()
    os.environ["ROS_MASTER_URI"] = master.uri
    part("master")
    options = RunOptions(scenario=Path(sys.argv[1]), clock=ClockMode.SYNC)
    world = build_world(options)
    part("world")
    settings = load_network_settings(None)
    node = Node("egosim", [])
    part("node")
    inbox = Inbox()
    bridge = Bridge(node, settings, HANDLERS, inbox, options.protocol)
    context = simulation_context(
        world, settings=settings, clock_mode=options.clock, data_roots=(Path.cwd(),),
        bridge=bridge, hold_output=node.holding_output, open_renderer=shared,
    )
    part("context")
    bridge.open(context)
    node.set_param("/use_sim_time", True)
    part("register")
    inbox.close()
    node.shutdown("done")
    master.shutdown()
    part("shutdown")
"""


def simulator_parts(runs: int) -> dict[str, dict[str, list[float]]]:
    found: dict[str, dict[str, list[float]]] = {}
    for _ in range(runs):
        lines = subprocess.run(
            [sys.executable, "-c", PARTS, str(SCENARIO)],
            check=True,
            capture_output=True,
            text=True,
        ).stdout.splitlines()
        case = "first"
        for line in lines:
            if line in ("first", "next"):
                case = line
                continue
            name, seconds = line.split()
            found.setdefault(name, {}).setdefault(case, []).append(float(seconds))
    return found


def process_cpu_s(command: list[str], env: dict[str, str] | None = None) -> float:
    """CPU time of running `command` to its end, interpreter start included."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run(command, check=True, env=env)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime


def stack_imports(runs: int) -> list[float] | None:
    """CPU time of the stack side's imports per run; None without Debian's rospy."""
    if subprocess.run(["/usr/bin/python3", "-c", "import rospy"], check=False).returncode:
        return None
    with tempfile.TemporaryDirectory() as temp:
        msgs = Path(temp) / "msgs"
        subprocess.run(
            [sys.executable, "-m", "egosim", "msgs", "--export-python", str(msgs)],
            check=True,
            capture_output=True,
        )
        env = {**os.environ, "PYTHONPATH": str(msgs)}
        command = ["/usr/bin/python3", "-c", "import rospy, morai_msgs.msg, morai_msgs.srv"]
        subprocess.run(command, check=True, env=env)  # the bytecode written once
        times = []
        for _ in range(runs):
            before = resource.getrusage(resource.RUSAGE_CHILDREN)
            subprocess.run(command, check=True, env=env)
            after = resource.getrusage(resource.RUSAGE_CHILDREN)
            times.append(after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime)
    return times


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=3)
    args = parser.parse_args()
    print(f"load average: {os.getloadavg()[0]:.1f}")
    print("| part | first case in a process: CPU (s) | next case, same process: CPU (s) |")
    print("|---|---:|---:|")
    totals = {"first": 0.0, "next": 0.0}
    for name, cases in simulator_parts(args.runs).items():
        cells = []
        for case in ("first", "next"):
            if case in cases:
                median = statistics.median(cases[case])
                totals[case] += median
                cells.append(f"{median:.3f}")
            else:
                cells.append("-")
        print(f"| {name} | {cells[0]} | {cells[1]} |")
    print(f"| total | {totals['first']:.3f} | {totals['next']:.3f} |")
    whole = [
        process_cpu_s([sys.executable, "-c", "import egosim.batch.simulate"])
        for _ in range(args.runs)
    ]
    print(f"a new interpreter importing egosim.batch.simulate: {statistics.median(whole):.3f} s")
    stack = stack_imports(args.runs)
    if stack is not None:
        print(f"stack side, rospy and morai_msgs imported: {statistics.median(stack):.3f} s")
    print(f"load average after: {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
