"""Timing of LaneMap queries on the built-in town and on a synthetic map of > 5000 lanes.

Run: .venv/bin/python benchmarks/map_queries.py
"""

from __future__ import annotations

import timeit

import numpy as np
from grid_map import grid_map

from egosim.world.map import LaneMap, build_builtin_map

SYNTHETIC_GRID = 16
SYNTHETIC_SPACING_M = 120.0
POINTS = 1000
# What the simulation loop projects each step with the default scenario: the ego's two
# points and the pedestrians on crosswalks.
STEP_POINTS = 5


def points_on_roads(lane_map: LaneMap, count: int, rng: np.random.Generator) -> tuple:
    """Random points within the lanes, with the lane heading as hint."""
    lanes = rng.integers(0, len(lane_map.lane_ids), count)
    poses = lane_map.poses_at(lanes, rng.uniform(0, 1, count) * lane_map.lane_lengths[lanes])
    lateral = rng.uniform(-1.5, 1.5, count)
    xy = poses[:, :2] + lateral[:, None] * np.column_stack(
        (-np.sin(poses[:, 3]), np.cos(poses[:, 3]))
    )
    return xy, poses[:, 3]


def measure(label: str, lane_map: LaneMap) -> None:
    rng = np.random.default_rng(1)
    xy, headings = points_on_roads(lane_map, POINTS, rng)
    single = min(
        timeit.repeat(
            lambda: [lane_map.project(x, y, h) for (x, y), h in zip(xy, headings, strict=True)],
            number=1,
            repeat=3,
        )
    )
    batch = min(timeit.repeat(lambda: lane_map.project_many(xy, headings), number=10, repeat=3))
    few, few_headings = xy[:STEP_POINTS], headings[:STEP_POINTS]
    step = min(
        timeit.repeat(lambda: lane_map.project_many(few, few_headings), number=1000, repeat=3)
    )
    xmin, ymin, xmax, ymax = lane_map.bounds()
    anywhere = rng.uniform((xmin, ymin), (xmax, ymax), size=(POINTS, 2))
    scattered = min(timeit.repeat(lambda: lane_map.project_many(anywhere), number=10, repeat=3))
    poses = min(
        timeit.repeat(
            lambda: lane_map.poses_at(np.zeros(POINTS, dtype=np.int64), np.linspace(0, 50, POINTS)),
            number=10,
            repeat=3,
        )
    )
    print(f"{label:>10}: {len(lane_map.lanes):5d} lanes")
    print(f"{'':>12}project (on road, heading hint)   {single / POINTS * 1e6:8.1f} us/call")
    print(f"{'':>12}project_many {STEP_POINTS} on-road points     {step / 1000 * 1e6:8.1f} us")
    print(f"{'':>12}project_many {POINTS} on-road points  {batch / 10 * 1e3:8.2f} ms")
    print(f"{'':>12}project_many {POINTS} points anywhere {scattered / 10 * 1e3:8.2f} ms")
    print(f"{'':>12}poses_at {POINTS}                    {poses / 10 * 1e3:8.2f} ms")


def main() -> None:
    for name, build in (
        ("town", lambda: build_builtin_map("town")),
        ("synthetic", lambda: grid_map(SYNTHETIC_GRID, SYNTHETIC_SPACING_M, name="synthetic")),
    ):
        seconds = min(timeit.repeat(build, number=1, repeat=2))
        print(f"{name:>10}: build {seconds * 1e3:.0f} ms")
        measure(name, build())


if __name__ == "__main__":
    main()
