"""Time per LiDAR scan with traffic around the ego vehicle.

Usage: .venv/bin/python benchmarks/lidar_cast.py [--boxes 100] [--repeats 30]
"""

from __future__ import annotations

import argparse
import statistics
import time

import numpy as np

from egosim.sensors import LidarConfig, LidarModel, ObstacleBoxes, Pose

CAR_SIZE_M = (4.5, 1.9, 1.6)


def traffic_around_ego(count: int, seed: int = 0) -> ObstacleBoxes:
    """The ego's own box first, then `count` cars scattered within 80 m."""
    rng = np.random.default_rng(seed)
    distance = rng.uniform(6.0, 80.0, count)
    bearing = rng.uniform(-np.pi, np.pi, count)
    centres = np.c_[distance * np.cos(bearing), distance * np.sin(bearing), np.full(count, 0.8)]
    return ObstacleBoxes(
        np.r_[[[0.0, 0.0, 0.8]], centres],
        np.tile(CAR_SIZE_M, (count + 1, 1)),
        np.r_[0.0, rng.uniform(-np.pi, np.pi, count)],
    )


def time_scans(model: LidarModel, scene: ObstacleBoxes, repeats: int) -> tuple[list[float], int]:
    points = model.scan(Pose(), scene, exclude_index=0)  # warm-up
    durations_ms = []
    for _ in range(repeats):
        start = time.perf_counter()
        model.scan(Pose(), scene, exclude_index=0)
        durations_ms.append((time.perf_counter() - start) * 1e3)
    return durations_ms, len(points)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--boxes", type=int, default=100)
    parser.add_argument("--repeats", type=int, default=30)
    args = parser.parse_args()

    scene = traffic_around_ego(args.boxes)
    print(f"{args.boxes} boxes within 80 m, 0.2 deg horizontal, 100 m range, {args.repeats} scans")
    for channels in (16, 64):
        model = LidarModel(LidarConfig(channels=channels))
        durations_ms, points = time_scans(model, scene, args.repeats)
        print(
            f"{channels:3d} channels ({model.beam_count} beams, {points} points): "
            f"median {statistics.median(durations_ms):.1f} ms, min {min(durations_ms):.1f} ms "
            "per scan"
        )


if __name__ == "__main__":
    main()
