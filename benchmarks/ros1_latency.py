"""Latency and throughput of egosim's TCPROS publisher against rospy's, both received by the
same rospy subscriber (Debian's ROS 1) on loopback.

    .venv/bin/python benchmarks/ros1_latency.py [--duration 5]

Each case publishes stamped messages (header.stamp = wall time at publish, serialization
included) at a fixed rate; the subscriber records arrival - stamp. "Flat out" cases publish
as fast as the publisher can for the duration and report the rate the subscriber received.
Prints a Markdown table.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import signal
import statistics
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from loopback import free_port

from egosim.msgs import MessageType, get_profile
from egosim.ros1 import Master, Node

ROS_PYTHON = "/usr/bin/python3"
PEERS = Path(__file__).resolve().parent.parent / "tests" / "ros1" / "peers"
CLOUD_BYTES = 1_000_000


@dataclass(frozen=True)
class Case:
    label: str
    msg_type: MessageType
    rate_hz: float  # 0: flat out
    cloud_bytes: int = 0


@dataclass
class Result:
    received: int
    median_ms: float
    p99_ms: float
    rate_hz: float


def spawn(args: list[str], env: dict[str, str]) -> subprocess.Popen[str]:
    return subprocess.Popen(
        [ROS_PYTHON, *args],
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.DEVNULL,
        text=True,
        start_new_session=True,
    )


def read_json(process: subprocess.Popen[str], key: str) -> dict[str, Any]:
    assert process.stdout is not None
    for line in process.stdout:
        if line.startswith("{") and key in (data := json.loads(line)):
            return data
    raise RuntimeError(f"peer {process.args} exited without printing {key}")


def stop(process: subprocess.Popen[str]) -> None:
    with contextlib.suppress(ProcessLookupError):
        os.killpg(process.pid, signal.SIGKILL)
    process.wait()


def summarize(summary: dict[str, Any]) -> Result:
    latencies = sorted(summary["latencies_ns"])
    count = len(latencies)
    span_s = (summary["last_ns"] - summary["first_ns"]) / 1e9
    return Result(
        received=count,
        median_ms=statistics.median(latencies) / 1e6,
        p99_ms=latencies[min(count - 1, int(count * 0.99))] / 1e6,
        rate_hz=(count - 1) / span_s if span_s > 0 else float("nan"),
    )


def new_message(case: Case) -> Any:
    message = case.msg_type.new()
    if case.cloud_bytes:
        message.height, message.point_step = 1, 16
        message.width = case.cloud_bytes // 16
        message.row_step = message.width * 16
        message.data = np.zeros(message.row_step, dtype=np.uint8)
    return message


def publish_egosim(node: Node, case: Case, duration: float, topic: str) -> None:
    pub = node.advertise(topic, case.msg_type, queue_size=100)
    message = new_message(case)
    while pub.num_subscribers < 1:
        time.sleep(0.01)
    time.sleep(0.5)
    period = 1.0 / case.rate_hz if case.rate_hz else 0.0
    start = time.perf_counter()
    sent = 0
    while time.perf_counter() - start < duration:
        now_ns = time.time_ns()
        message.header.seq = sent
        message.header.stamp.sec, message.header.stamp.nanosec = divmod(now_ns, 1_000_000_000)
        pub.publish(case.msg_type.serialize(message))
        sent += 1
        if period and (delay := start + sent * period - time.perf_counter()) > 0:
            time.sleep(delay)
    time.sleep(0.5)
    pub.close()


def run_case(case: Case, publisher: str, env: dict[str, str], duration: float, n: int) -> Result:
    topic = f"/bench{n}"
    listener = spawn([str(PEERS / "latency_listener.py"), topic], env)
    try:
        read_json(listener, "event")
        if publisher == "egosim":
            node = Node(
                "egosim_bench",
                master_uri=env["ROS_MASTER_URI"],
                embedded_master="never",
                rosout_logger=None,
            )
            try:
                publish_egosim(node, case, duration, topic)
            finally:
                node.shutdown()
        else:
            with tempfile.NamedTemporaryFile("w", suffix=".msg", delete=False) as definition:
                definition.write(case.msg_type.definition)
            args = [str(PEERS / "stamped_talker.py"), topic, case.msg_type.name, definition.name]
            args += ["--rate", str(case.rate_hz), "--duration", str(duration)]
            args += ["--cloud-bytes", str(case.cloud_bytes)]
            talker = spawn(args, env)
            try:
                read_json(talker, "sent")
            finally:
                stop(talker)
                os.unlink(definition.name)
        return summarize(read_json(listener, "latencies_ns"))
    finally:
        stop(listener)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--duration", type=float, default=5.0, help="seconds per case")
    args = parser.parse_args()
    profile = get_profile("26.r1")
    ego = profile.message("morai_msgs/EgoVehicleStatus")
    cloud = profile.message("sensor_msgs/PointCloud2")
    cases = [
        Case("EgoVehicleStatus 100 Hz", ego, 100),
        Case("EgoVehicleStatus 1 kHz", ego, 1000),
        Case("PointCloud2 1 MB 10 Hz", cloud, 10, CLOUD_BYTES),
        Case("EgoVehicleStatus flat out", ego, 0),
        Case("PointCloud2 1 MB flat out", cloud, 0, CLOUD_BYTES),
    ]
    with tempfile.TemporaryDirectory() as home:
        master = Master(f"http://127.0.0.1:{free_port()}/").start()
        env = {k: v for k, v in os.environ.items() if not k.startswith("ROS_")}
        env.update(ROS_MASTER_URI=master.uri, ROS_HOME=home, ROS_LOG_DIR=home, PYTHONUNBUFFERED="1")
        size = len(ego.serialize(ego.new()))
        print(
            f"EgoVehicleStatus: {size} bytes; PointCloud2: {CLOUD_BYTES} bytes of data; "
            f"{args.duration:g} s per case; subscriber: rospy (tcp_nodelay)\n"
        )
        columns = ["case", "publisher", "received", "median latency (ms)", "p99 latency (ms)"]
        print("| " + " | ".join([*columns, "received rate (Hz)"]) + " |")
        print("|---|---|---:|---:|---:|---:|")
        try:
            for n, case in enumerate(cases):
                for publisher in ("egosim", "rospy"):
                    result = run_case(case, publisher, env, args.duration, n)
                    print(
                        f"| {case.label} | {publisher} | {result.received} "
                        f"| {result.median_ms:.3f} | {result.p99_ms:.3f} | {result.rate_hz:.0f} |",
                        flush=True,
                    )
        finally:
            master.shutdown()


if __name__ == "__main__":
    sys.exit(main())
