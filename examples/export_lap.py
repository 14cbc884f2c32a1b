"""Write the waypoints of a lap of egosim's town to a CSV file (x, y in the map frame, m).

The lap circles the block south of the town centre clockwise, keeping to the outer
lane and turning right at junctions 7, 3, 2 and 6. Run with egosim installed:

    python examples/export_lap.py examples/town_block_lap.csv
"""

from __future__ import annotations

import csv
import sys

import numpy as np

from egosim.world.map import build_builtin_map

START_LANE = "R5_E_2"
SPACING_M = 1.0


def lap_lanes(lane_map, start: str) -> list[str]:
    """Follow right turns (or the only way on) from `start` until back at it."""
    lanes = [start]
    while True:
        successors = lane_map.lane(lanes[-1]).successors
        following = next((s for s in successors if "_right_" in s), successors[0])
        if following == start:
            return lanes
        lanes.append(following)


def main(path: str) -> None:
    lane_map = build_builtin_map("town")
    points = []
    for lane_id in lap_lanes(lane_map, START_LANE):
        length = lane_map.lane(lane_id).length
        for s in np.arange(0.0, length, SPACING_M):
            x, y, _, _ = lane_map.pose_at(lane_id, float(s))
            points.append((round(x, 3), round(y, 3)))
    with open(path, "w", newline="") as file:
        csv.writer(file).writerows([("x", "y"), *points])
    print(f"{len(points)} waypoints written to {path}")


if __name__ == "__main__":
    main(sys.argv[1])
