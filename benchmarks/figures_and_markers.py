"""What egosim's pictures cost: the map picture (`egosim map --png`), a drive report
(`egosim report`), and the /egosim/markers messages (the map once, the scene at 10 Hz).

Each figure is the best of REPEATS runs (wall time, this process); sizes are bytes.
Run: .venv/bin/python benchmarks/figures_and_markers.py
"""

from __future__ import annotations

import tempfile
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from egosim.bridge import simulation_context
from egosim.bridge.scene.markers import build_map_markers, build_scene_markers
from egosim.msgs import get_profile
from egosim.plots import figure_png, map_figure, write_report
from egosim.report import RecordedDrive, drive_report_blocks
from egosim.world import World
from egosim.world.map import build_builtin_map
from egosim.world.scenario import load_default_scenario

REPEATS = 3
DRIVE_S = 60.0
EGO_HZ = 50


def best(run: Callable[[], Any]) -> tuple[float, Any]:
    times, result = [], None
    for _ in range(REPEATS):
        start = time.perf_counter()
        result = run()
        times.append(time.perf_counter() - start)
    return min(times), result


def synthetic_drive() -> RecordedDrive:
    """A minute along the town's R1_E_1 and on, weaving 0.3 m about the lane centre."""
    t = np.arange(int(DRIVE_S * EGO_HZ)) / EGO_HZ
    return RecordedDrive(
        path=Path("synthetic.bag"),
        profile="26.r1",
        times_s=t,
        x=-256.0 + 8.0 * t,
        y=-271.75 + 0.3 * np.sin(t),
        heading=np.arctan2(0.3 * np.cos(t), 8.0),
        speed_mps=np.full_like(t, 8.0),
        accel_pedal=np.full_like(t, 0.2),
        brake_pedal=np.zeros_like(t),
        front_steer_rad=0.01 * np.cos(t),
        collisions=(),
        light_states=(),
    )


def main() -> None:
    print(f"best of {REPEATS}")
    for name in ("town", "loop"):
        lane_map = build_builtin_map(name)
        seconds, (figure, _) = best(lambda lane_map=lane_map: map_figure(lane_map))
        png_seconds, png = best(lambda figure=figure: figure_png(figure))
        print(
            f"map picture {name}: draw {seconds * 1e3:.0f} ms, PNG {png_seconds * 1e3:.0f} ms, "
            f"{len(png) / 1e3:.0f} kB"
        )
    town = build_builtin_map("town")
    drive = synthetic_drive()
    with tempfile.TemporaryDirectory() as folder:
        page = Path(folder) / "report.html"
        seconds, written = best(
            lambda: write_report(page, "drive", drive_report_blocks(drive, town))
        )
        sizes = ", ".join(f"{p.name} {p.stat().st_size / 1e3:.0f} kB" for p in written)
    print(f"report of a {DRIVE_S:.0f} s drive at {EGO_HZ} Hz: {seconds * 1e3:.0f} ms ({sizes})")
    profile = get_profile("26.r1")
    array = profile.message("visualization_msgs/MarkerArray")
    context = simulation_context(World(town, load_default_scenario()))
    row = context.row("markers")
    for label, build in (("map (once)", build_map_markers), ("scene (10 Hz)", build_scene_markers)):
        build_s, message = best(lambda build=build: build(context, row))
        serialize_s, data = best(lambda message=message: array.serialize(message))
        print(
            f"/egosim/markers {label}, town: {len(message.markers)} markers, "
            f"{len(data) / 1e3:.1f} kB, build {build_s * 1e3:.2f} ms, "
            f"serialize {serialize_s * 1e3:.2f} ms"
        )


if __name__ == "__main__":
    main()
