"""rich against tqdm for `egosim batch`'s progress bar: import time (fresh interpreter)
and the cost of one update drawn to a terminal (a StringIO standing in for it).

Usage: .venv/bin/pip install tqdm && .venv/bin/python benchmarks/progress_bars.py
(tqdm is not a dependency: this script is what chose rich.)
"""

from __future__ import annotations

import io
import subprocess
import sys
import time

from rich.console import Console
from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn
from tqdm import tqdm

UPDATES = 20000


def import_s(module: str) -> float:
    code = f"import time; t = time.perf_counter(); import {module}; print(time.perf_counter() - t)"
    runs = [
        float(subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                             check=True).stdout)
        for _ in range(5)
    ]  # fmt: skip
    return sorted(runs)[2]


def rich_update_us() -> float:
    console = Console(file=io.StringIO(), force_terminal=True, width=100)
    with Progress(TextColumn("batch"), BarColumn(), MofNCompleteColumn(), console=console) as bar:
        task = bar.add_task("cases", total=UPDATES)
        start = time.perf_counter()
        for k in range(UPDATES):
            bar.update(task, completed=k + 1)
        return (time.perf_counter() - start) / UPDATES * 1e6


def tqdm_update_us() -> float:
    with tqdm(total=UPDATES, file=io.StringIO(), mininterval=0.1) as bar:
        start = time.perf_counter()
        for _ in range(UPDATES):
            bar.update(1)
        return (time.perf_counter() - start) / UPDATES * 1e6


def main() -> None:
    print("| library | import (ms, median of 5) | update (µs) |")
    print("|---|---:|---:|")
    print(f"| rich | {import_s('rich.progress') * 1e3:.0f} | {rich_update_us():.1f} |")
    print(f"| tqdm | {import_s('tqdm') * 1e3:.0f} | {tqdm_update_us():.1f} |")


if __name__ == "__main__":
    main()
