"""MORAI SIM scenario files: reading one of N NPCs, N pedestrians and N objects, and what
their active distances cost a World.step (the wake check of dormant NPCs and pedestrians).

Usage: .venv/bin/python benchmarks/morai_scenario.py [--entries 200] [--steps 500]
"""

from __future__ import annotations

import argparse
import json
import math
import statistics
import time
from typing import Any

import numpy as np

from egosim.world import World
from egosim.world.map import LaneMap, build_builtin_map
from egosim.world.scenario.morai import read_morai_scenario

TOWN_ORIGIN = (313000.0, 4161000.0)


def document(town: LaneMap, entries: int, active_distance: float) -> dict[str, Any]:
    """`entries` NPCs spread over the road lanes (by link and ratio), as many pedestrians
    and cones beside them (6 m and 8 m to the right), every NPC and pedestrian waiting for
    the ego to come within `active_distance` m (MORAI writes 999 for "at once")."""
    lane_ids = [lane.id for lane in town.lanes.values() if not lane.is_junction]

    def ratio(k: int) -> float:
        return 0.1 + 0.8 * (k // len(lane_ids)) / max(1, entries // len(lane_ids))

    def beside(k: int, right_m: float) -> dict[str, Any]:
        lane = lane_ids[k % len(lane_ids)]
        x, y, _, heading = town.pose_at(lane, ratio(k) * town.lanes[lane].length)
        return point(x + right_m * math.sin(heading), y - right_m * math.cos(heading))

    def link(k: int) -> dict[str, Any]:
        return {
            "initPositionMode": "Link",
            "initLink": lane_ids[k % len(lane_ids)],
            "initLinkRatio": ratio(k),
            "gear": 4,
        }

    def point(x: float, y: float, z: float = 0.0) -> dict[str, Any]:
        return {"x": x, "y": y, "z": z, "_x": f"{x:.3f}", "_y": f"{y:.3f}", "_z": f"{z:.3f}"}

    rot = {"roll": "0.000", "pitch": "0.000", "yaw": "90.000"}
    return {
        "version": 1.0,
        "egoVehicle": {"DataID": 20200003, "initPosition": link(0), "currentVelocity": 0.0},
        "vehicleList": [
            {
                "DataID": 30100010,
                "UNIQUEID": k,
                "initPosition": link(k + 1),
                "velocityType": 2,
                "desiredVelocity": 30.0,
                "activeDistance": active_distance,
            }
            for k in range(entries)
        ],
        "pedestrianList": [
            {
                "DataID": 50100001,
                "UNIQUEID": 10_000 + k,
                "pos": beside(k, 6.0),
                "rot": rot,
                "speed": 4.0,
                "activeDistance": active_distance,
                "active": True,
                "movingDistance": 5.0,
                "isWaypointMode": False,
            }
            for k in range(entries)
        ],
        "objectList": [
            {
                "DataID": 40100005,
                "UNIQUEID": 20_000 + k,
                "pos": beside(k, 8.0),
                "rot": rot,
                "scale": point(1.0, 1.0, 1.0),
            }
            for k in range(entries)
        ],
        "mapInfo": {
            "mapName": "town",
            "eastOffset": TOWN_ORIGIN[0],
            "northOffset": TOWN_ORIGIN[1],
            "globalCoordinateSystem": "UTM52N",
        },
    }


def median_ms(samples: list[float]) -> str:
    return f"{statistics.median(samples) * 1e3:.3f} ms"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--entries", type=int, default=200)
    parser.add_argument("--steps", type=int, default=500)
    args = parser.parse_args()
    town = build_builtin_map("town")

    text = json.dumps(document(town, args.entries, 999.0), indent=2)
    reads = []
    for _ in range(20):
        started = time.perf_counter()
        read_morai_scenario(text, "bench.json")
        reads.append(time.perf_counter() - started)
    print(
        f"read {len(text) / 1e3:.0f} kB, {args.entries} each of NPCs, pedestrians, objects:"
        f" {median_ms(reads)} median of 20"
    )

    for label, distance in (("dormant (active distance 1 m)", 1.0), ("active (999 m)", 999.0)):
        scenario = read_morai_scenario(json.dumps(document(town, args.entries, distance))).scenario
        world = World(town, scenario)
        steps = []
        for _ in range(args.steps):
            started = time.perf_counter()
            world.step(0.01)
            steps.append(time.perf_counter() - started)
        print(f"World.step, {args.entries} NPCs and pedestrians {label}: {median_ms(steps)}")
    # The wake check alone, as World.step runs it while any of them is dormant.
    points = np.array([(world.ego_status().pose.x, world.ego_status().pose.y)])
    dormant = World(
        town, read_morai_scenario(json.dumps(document(town, args.entries, 1.0))).scenario
    )
    checks = []
    for _ in range(args.steps):
        started = time.perf_counter()
        dormant.npcs.wake(points)
        dormant.pedestrians.wake(points)
        checks.append(time.perf_counter() - started)
    print(f"wake check of {args.entries} dormant NPCs and pedestrians: {median_ms(checks)}")


if __name__ == "__main__":
    main()
