"""Load time of a large MGeo map: a ~3 MB link_set.json of thousands of links.

The map is a synthetic grid of signalised junctions (the built-in road builder), written
out as an MGeo folder by egosim's MGeo writer: centrelines resampled every metre, as MGeo
tools write them, lane boundaries, nodes, lights, synced light sets, intersection
controllers and crosswalks.

Run: .venv/bin/python benchmarks/map_load.py
"""

from __future__ import annotations

import json
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

from grid_map import grid_map

from egosim.maps import read_map
from egosim.world.map.mgeo import build_mgeo_map, mgeo_files

GRID = 10
SPACING_M = 150.0
POINT_SPACING_M = 1.0


def best_of(repeats: int, action: Callable[[], object]) -> float:
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        action()
        times.append(time.perf_counter() - start)
    return min(times)


def main() -> None:
    files = mgeo_files(grid_map(GRID, SPACING_M), POINT_SPACING_M)
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp) / "grid"
        folder.mkdir()
        for name, content in files.items():
            (folder / name).write_text(json.dumps(content))
        link_bytes = (folder / "link_set.json").stat().st_size
        all_bytes = sum(p.stat().st_size for p in folder.iterdir())
        parse = best_of(3, lambda: [json.loads(p.read_bytes()) for p in folder.iterdir()])
        build = best_of(3, lambda: build_mgeo_map("grid", files, []))
        # Widths from lane boundaries (every road link names two) instead of width fields.
        unbounded = {n: c for n, c in files.items() if n != "lane_boundary_set.json"}
        build_unbounded = best_of(3, lambda: build_mgeo_map("grid", unbounded, []))
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
    print(f"    without lane boundaries: {build_unbounded * 1e3:8.1f} ms")
    print(f"  read_map (read + build)  : {total * 1e3:8.1f} ms")


if __name__ == "__main__":
    main()
