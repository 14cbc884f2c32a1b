"""CPU a 30 Hz camera costs in a real-time run of the town, watched and unwatched.

Starts `egosim run` (town, default scenario, real-time clock) for the same wall time
with no subscriber, with a subscriber to /image_jpeg/compressed (640 x 480 JPEG, 30 Hz)
and, as a base, with `cameras: []` in the network settings; `--repeats` rounds of the
three, interleaved so that a busy spell on the machine does not land on one of them.
Reports the simulator's CPU time per wall second (user + system, from /proc), median
over the rounds, the frames the subscriber received, and the camera's share: watched
minus unwatched.

Usage: .venv/bin/python benchmarks/camera_cpu.py [--seconds 20] [--repeats 3]
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path
from statistics import median

from loopback import free_port

from egosim.msgs import get_profile
from egosim.ros1 import Node

CLOCK_TICKS = os.sysconf("SC_CLK_TCK")


def cpu_seconds(pid: int) -> float:
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / CLOCK_TICKS


def measure(seconds: float, watch: bool, network: Path | None) -> tuple[float, int]:
    uri = f"http://127.0.0.1:{free_port()}/"
    env = dict(os.environ, ROS_MASTER_URI=uri, ROS_IP="127.0.0.1")
    command = [sys.executable, "-m", "egosim", "run", "--log-level", "WARNING"]
    if network is not None:
        command += ["--network", str(network)]
    process = subprocess.Popen(command, env=env, stdout=subprocess.PIPE, text=True)
    assert process.stdout is not None
    for line in process.stdout:
        if line.strip() == "egosim: ready":
            break
    frames = 0
    lock = threading.Lock()
    node = None
    if watch:
        os.environ["ROS_MASTER_URI"] = uri
        node = Node("camera_cpu_watcher", [])

        def received(data: bytes, header: object) -> None:
            nonlocal frames
            with lock:
                frames += 1

        image_type = get_profile("26.r1").message("sensor_msgs/CompressedImage")
        node.subscribe("/image_jpeg/compressed", image_type, received)
    time.sleep(3.0)
    with lock:
        frames = 0
    start_cpu, start = cpu_seconds(process.pid), time.monotonic()
    time.sleep(seconds)
    used = (cpu_seconds(process.pid) - start_cpu) / (time.monotonic() - start)
    with lock:
        received_frames = frames
    if node is not None:
        node.shutdown("done")
    process.terminate()
    process.wait(timeout=30)
    return used, received_frames


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=20.0)
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    base, unwatched, watched, frames = [], [], [], []
    with tempfile.TemporaryDirectory() as folder:
        no_cameras = Path(folder) / "no_cameras.yaml"
        no_cameras.write_text("sensors:\n  cameras: []\n")
        for _ in range(args.repeats):
            base.append(measure(args.seconds, False, no_cameras)[0])
            unwatched.append(measure(args.seconds, False, None)[0])
            used, received = measure(args.seconds, True, None)
            watched.append(used)
            frames.append(received)
    rounds = f"median of {args.repeats}"
    print(f"no camera configured: {100 * median(base):.0f} % of a core ({rounds})")
    print(f"camera, no subscriber: {100 * median(unwatched):.0f} % of a core ({rounds})")
    print(
        f"camera, one subscriber: {100 * median(watched):.0f} % of a core ({rounds}; "
        f"{median(frames) / args.seconds:.1f} frames/s received)"
    )
    shares = [w - u for w, u in zip(watched, unwatched, strict=True)]
    print(
        f"the watched camera's share: {100 * median(shares):.0f} % of a core "
        f"(rounds: {', '.join(f'{100 * x:.0f}' for x in shares)})"
    )


if __name__ == "__main__":
    main()
