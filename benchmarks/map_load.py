"""Load time of a large MGeo map: a ~3 MB link_set.json of thousands of links.

The map is a synthetic grid of signalised junctions (the built-in road builder), written
out as an MGeo folder with centrelines resampled every metre, as MGeo tools write them,
plus its nodes, lights, synced light sets and intersection controllers.

Run: .venv/bin/python benchmarks/map_load.py
"""

from __future__ import annotations

import json
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np
from grid_map import grid_map

from egosim.maps import read_map
from egosim.world.map import LaneMap
from egosim.world.map.mgeo import build_mgeo_map
from egosim.world.map.polyline import stations

GRID = 10
SPACING_M = 150.0
POINT_SPACING_M = 1.0
SUB_TYPES = {
    0: ["red", "yellow", "straight"],
    1: ["red", "yellow", "left"],
    2: ["red", "yellow", "left", "straight"],
    100: ["yellow"],
}


def resampled(points: np.ndarray) -> list[list[float]]:
    s = stations(points)
    ts = np.unique(np.append(np.arange(0.0, s[-1], POINT_SPACING_M), s[-1]))
    return [[round(float(np.interp(t, s, points[:, k])), 3) for k in range(3)] for t in ts]


def mgeo_folder(lane_map: LaneMap) -> dict[str, object]:
    nodes: dict[tuple[float, float], str] = {}

    def node(point: np.ndarray) -> str:
        key = (round(float(point[0]), 2), round(float(point[1]), 2))
        return nodes.setdefault(key, f"N{len(nodes):06d}")

    links = []
    for lane in lane_map.lanes.values():
        links.append(
            {
                "idx": lane.id,
                "from_node_idx": node(lane.centerline[0]),
                "to_node_idx": node(lane.centerline[-1]),
                "points": resampled(lane.centerline),
                "max_speed": round(lane.speed_limit * 3.6),
                "link_type": "1",
                "road_id": lane.id.split("_")[0],
                "ego_lane": 1,
                "can_move_left_lane": lane.left_neighbor is not None,
                "can_move_right_lane": lane.right_neighbor is not None,
                "left_lane_change_dst_link_idx": lane.left_neighbor,
                "right_lane_change_dst_link_idx": lane.right_neighbor,
                "lane_ch_link_path": [],
                "related_signal": [],
                "width_start": 3.5,
                "width_end": 3.5,
                "force_width_start": False,
                "force_width_end": False,
            }
        )
    stop_nodes = {
        links[lane_map.lane_index(i)]["to_node_idx"]
        for t in lane_map.traffic_lights.values()
        for i in t.lane_ids
    }
    return {
        "global_info.json": {
            "maj_ver": 2,
            "min_ver": 1,
            "global_coordinate_system": "UTM52N",
            "local_origin_in_global": [313000.0, 4161000.0, 0.0],
        },
        "node_set.json": [
            {
                "idx": idx,
                "point": [x, y, 0.0],
                "node_type": 1,
                "junction": [],
                "on_stop_line": idx in stop_nodes,
            }
            for (x, y), idx in nodes.items()
        ],
        "link_set.json": links,
        "traffic_light_set.json": [
            {
                "idx": t.id,
                "link_id_list": list(t.lane_ids),
                "point": list(t.position),
                "type": "car",
                "sub_type": SUB_TYPES[t.light_type],
            }
            for t in lane_map.traffic_lights.values()
        ],
        "synced_traffic_light_set.json": [
            {
                "idx": f"SL{site.id}_{k}",
                "signal_id_list": list(group),
                "intersection_controller_id": f"IntTL{site.id}",
                "point": [*site.center, 0.0],
            }
            for site in lane_map.intersections.values()
            for k, group in enumerate(site.approach_groups)
        ],
        "intersection_controller_set.json": [
            {
                "idx": f"IntTL{site.id}",
                "point": [*site.center, 0.0],
                "synced_signal_id_list": [
                    f"SL{site.id}_{k}" for k in range(len(site.approach_groups))
                ],
            }
            for site in lane_map.intersections.values()
        ],
    }


def best_of(repeats: int, action: Callable[[], object]) -> float:
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        action()
        times.append(time.perf_counter() - start)
    return min(times)


def main() -> None:
    files = mgeo_folder(grid_map(GRID, SPACING_M))
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp) / "grid"
        folder.mkdir()
        for name, content in files.items():
            (folder / name).write_text(json.dumps(content))
        link_bytes = (folder / "link_set.json").stat().st_size
        all_bytes = sum(p.stat().st_size for p in folder.iterdir())
        parse = best_of(3, lambda: [json.loads(p.read_bytes()) for p in folder.iterdir()])
        build = best_of(3, lambda: build_mgeo_map("grid", files, []))
        total = best_of(3, lambda: read_map(str(folder)))
        lane_map = read_map(str(folder)).lane_map
    links: list[dict] = files["link_set.json"]  # type: ignore[assignment]
    points = sum(len(link["points"]) for link in links)
    print(
        f"MGeo folder: link_set.json {link_bytes / 1e6:.2f} MB "
        f"({len(links)} links, {points} points)"
    )
    print(f"  all files {all_bytes / 1e6:.2f} MB")
    print(
        f"  lanes {len(lane_map.lanes)}, lights {len(lane_map.traffic_lights)}, "
        f"intersections {len(lane_map.intersections)}"
    )
    print(f"  json.loads of every file : {parse * 1e3:8.1f} ms")
    print(f"  build_mgeo_map           : {build * 1e3:8.1f} ms")
    print(f"  read_map (read + build)  : {total * 1e3:8.1f} ms")


if __name__ == "__main__":
    main()
