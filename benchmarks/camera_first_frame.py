"""The cameras' first frame: building the camera rig, the first image, the images after it.

Each round is a process of its own, so the OpenGL context, its shaders and the map's scene
are all made anew, as when `egosim run` starts: the town with its default scenario, the
default front camera (640 x 480 RGB), `simulation_context` with the OpenGL renderer (the
sensor and camera rigs), then camera 0's image FRAMES times. Wall and CPU time (every
thread of the process, the rasteriser's included) of each part; medians over the rounds.

Usage: .venv/bin/python benchmarks/camera_first_frame.py [--rounds 5] [--frames 30]
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import time
from collections.abc import Callable


def _timed(action: Callable[[], object]) -> tuple[float, float]:
    """(wall ms, CPU ms) of one call."""
    wall, cpu = time.perf_counter(), time.process_time()
    action()
    return (time.perf_counter() - wall) * 1e3, (time.process_time() - cpu) * 1e3


def one_round(frames: int) -> dict[str, float]:
    from egosim.bridge import simulation_context  # noqa: PLC0415 - timed in the round
    from egosim.render import open_renderer  # noqa: PLC0415
    from egosim.world import World  # noqa: PLC0415
    from egosim.world.map import build_builtin_map  # noqa: PLC0415
    from egosim.world.scenario import load_default_scenario  # noqa: PLC0415

    world = World(build_builtin_map("town"), load_default_scenario())
    world.step()
    built: list[object] = []
    rig_wall, rig_cpu = _timed(
        lambda: built.append(simulation_context(world, open_renderer=open_renderer))
    )
    context = built[0]
    cameras, sensors = context.cameras, context.sensors  # type: ignore[attr-defined]
    assert cameras is not None, "no camera renders here"

    def image() -> object:
        return cameras.image(sensors, world, 0)

    first_wall, first_cpu = _timed(image)
    later = [_timed(image) for _ in range(frames)]
    return {
        "rig_wall_ms": rig_wall,
        "rig_cpu_ms": rig_cpu,
        "first_wall_ms": first_wall,
        "first_cpu_ms": first_cpu,
        "later_wall_ms": statistics.median(wall for wall, _ in later),
        "later_cpu_ms": statistics.median(cpu for _, cpu in later),
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--frames", type=int, default=30)
    parser.add_argument("--one-round", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.one_round:
        print(json.dumps(one_round(args.frames)))
        return
    rounds = [
        json.loads(
            subprocess.run(
                [sys.executable, __file__, "--one-round", "--frames", str(args.frames)],
                check=True,
                capture_output=True,
                text=True,
            ).stdout
        )
        for _ in range(args.rounds)
    ]
    for part, name in (
        ("rig", "simulation_context (rigs, renderer, scene)"),
        ("first", "first image"),
        ("later", f"each of the next {args.frames} images"),
    ):
        wall = statistics.median(r[f"{part}_wall_ms"] for r in rounds)
        cpu = statistics.median(r[f"{part}_cpu_ms"] for r in rounds)
        spread = ", ".join(f"{r[f'{part}_wall_ms']:.1f}" for r in rounds)
        print(f"{name}: wall {wall:.1f} ms ({spread}), CPU {cpu:.1f} ms")


if __name__ == "__main__":
    main()
