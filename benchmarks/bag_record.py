"""Recording and replay costs: BagRecorder.write per call, sustained rate, BagTimeline.sample.

Usage: .venv/bin/python benchmarks/bag_record.py [--messages 200000] [--minutes 10]
"""

from __future__ import annotations

import argparse
import math
import statistics
import tempfile
import time
from pathlib import Path
from typing import Any

import numpy as np

from egosim.msgs import get_profile
from egosim.replay import BagRecorder, BagTimeline

PROFILE = get_profile("26.r1")
EGO = PROFILE.message("morai_msgs/EgoVehicleStatus")
OBJECTS = PROFILE.message("morai_msgs/ObjectStatusList")
OBJECT = PROFILE.message("morai_msgs/ObjectStatus").make
VECTOR = PROFILE.message("geometry_msgs/Vector3").make
OBJECTS_PER_LIST = 20


def ego_bytes(t: float) -> bytes:
    message = EGO.new(heading=math.degrees(t % math.tau), position=VECTOR(x=t, y=2 * t, z=0.0))
    message.header.stamp.sec, message.header.stamp.nanosec = divmod(round(t * 1e9), 10**9)
    return EGO.serialize(message)


def objects_bytes(t: float) -> bytes:
    npcs = [
        OBJECT(
            unique_id=k,
            type=1,
            name=f"npc#{k}",
            heading=0.0,
            velocity=VECTOR(x=36.0, y=0.0, z=0.0),
            acceleration=VECTOR(x=0.0, y=0.0, z=0.0),
            size=VECTOR(x=1.8, y=4.5, z=1.5),
            position=VECTOR(x=10.0 * k + 10.0 * t, y=3.5, z=0.0),
        )
        for k in range(OBJECTS_PER_LIST)
    ]
    message = OBJECTS.new(num_of_npcs=len(npcs), npc_list=npcs)
    message.header.stamp.sec, message.header.stamp.nanosec = divmod(round(t * 1e9), 10**9)
    return OBJECTS.serialize(message)


def add_topics(recorder: BagRecorder) -> tuple[Any, Any]:
    return (
        recorder.add_connection("/Ego_topic", EGO.name, EGO.md5sum, EGO.definition),
        recorder.add_connection("/Object_topic", OBJECTS.name, OBJECTS.md5sum, OBJECTS.definition),
    )


def bench_write(directory: Path, count: int) -> None:
    ego_data, objects_data = ego_bytes(0.0), objects_bytes(0.0)
    batch = 1000
    recorder = BagRecorder(directory / "write.bag", queue_limit=count + 1, queue_bytes=2**34)
    ego, objects = add_topics(recorder)
    per_call_us = []
    started = time.perf_counter()
    for first in range(0, count, batch):
        start = time.perf_counter()
        for k in range(first, first + batch):
            if k % 4:
                recorder.write(ego, k * 20_000_000, ego_data)
            else:
                recorder.write(objects, k * 20_000_000, objects_data)
        per_call_us.append((time.perf_counter() - start) / batch * 1e6)
    queued = time.perf_counter() - started
    stats = recorder.close()
    total = time.perf_counter() - started
    size_mb = (directory / "write.bag").stat().st_size / 1e6
    print(
        f"write(): median {statistics.median(per_call_us):.2f} us/call, "
        f"p95 {np.percentile(per_call_us, 95):.2f} us/call over {count} calls "
        f"({queued:.2f} s to queue)"
    )
    print(
        f"sustained: {stats.written / total:,.0f} messages/s, "
        f"{size_mb / total:.1f} MB/s into the bag "
        f"({stats.written} messages, {size_mb:.1f} MB, {stats.chunks} chunks, "
        f"{stats.dropped} dropped, {total:.2f} s including close)"
    )


def bench_sample(directory: Path, minutes: float) -> None:
    path = directory / "drive.bag"
    seconds = minutes * 60
    events = [(k / 50, 0) for k in range(int(seconds * 50) + 1)]
    events += [(k / 20, 1) for k in range(int(seconds * 20) + 1)]
    with BagRecorder(path) as recorder:
        handles = add_topics(recorder)
        for t, topic in sorted(events):
            data = ego_bytes(t) if topic == 0 else objects_bytes(t)
            recorder.write(handles[topic], round(t * 1e9), data)
    start = time.perf_counter()
    timeline = BagTimeline.open(path)
    opened = time.perf_counter() - start
    rng = np.random.default_rng(0)
    instants = rng.uniform(0.0, timeline.duration, 20_000).tolist()
    start = time.perf_counter()
    for t in instants:
        timeline.sample(t)
    per_sample_us = (time.perf_counter() - start) / len(instants) * 1e6
    assert timeline.ego is not None and timeline.objects is not None
    print(
        f"BagTimeline.open: {opened:.2f} s for {minutes:g} min "
        f"({len(timeline.ego)} ego + {len(timeline.objects)} object lists)"
    )
    print(f"BagTimeline.sample: {per_sample_us:.1f} us/sample with {OBJECTS_PER_LIST} objects")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--messages", type=int, default=200_000)
    parser.add_argument("--minutes", type=float, default=10.0)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as directory:
        bench_write(Path(directory), args.messages)
        bench_sample(Path(directory), args.minutes)


if __name__ == "__main__":
    main()
