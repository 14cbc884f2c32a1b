"""How much a recording loses when `egosim run --record` is killed with SIGKILL.

Starts `egosim run --record` (town, real time, so header stamps are wall-clock times),
lets it record for `--seconds`, kills it with SIGKILL, repairs the bag, and reports
the gap between the kill and the newest message the bag kept (what was lost), over
`--runs` runs.

Usage: .venv/bin/python benchmarks/record_kill.py [--runs 5] [--seconds 3]
"""

from __future__ import annotations

import argparse
import signal
import statistics
import tempfile
import time
from pathlib import Path

from loopback import start_simulator
from rosbags.rosbag1 import Reader

from egosim.replay import repair_bag


def loss_of_one_run(seconds: float, folder: Path) -> tuple[float, int]:
    """(seconds of messages lost, messages kept) for one killed recording."""
    bag = folder / f"killed-{time.monotonic_ns()}.bag"
    process = start_simulator("--record", str(bag))
    time.sleep(seconds)
    killed_at = time.time()
    process.send_signal(signal.SIGKILL)
    process.wait(10)
    repair_bag(bag)
    with Reader(bag) as reader:
        stamps = [stamp for _, stamp, _ in reader.messages()]
    return killed_at - max(stamps) / 1e9, len(stamps)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--seconds", type=float, default=3.0)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        results = [loss_of_one_run(args.seconds, Path(folder)) for _ in range(args.runs)]
    losses = [loss * 1000 for loss, _ in results]
    print(f"{args.runs} runs of {args.seconds:.0f} s recording, killed with SIGKILL:")
    print(
        f"  lost: median {statistics.median(losses):.0f} ms, max {max(losses):.0f} ms "
        f"(kept {min(kept for _, kept in results)}..{max(kept for _, kept in results)} messages)"
    )


if __name__ == "__main__":
    main()
