"""Costs of recording and replaying on the loop thread, over the town's default scenario.

- the recording tap per message (what `--record` adds to each publish),
- World.step alone vs advance_replay + World.step while a bag plays (all targets),
- building one ReplayInfo.

Usage: .venv/bin/python benchmarks/replay_rows.py [--seconds 20]
"""

from __future__ import annotations

import argparse
import statistics
import tempfile
import time
from pathlib import Path

from egosim.app.recording import TopicRecorder, open_recorder
from egosim.bridge import simulation_context
from egosim.bridge.context import BridgeContext
from egosim.bridge.egos.ego import publish_ego_status
from egosim.bridge.replay.replay_rows import advance_replay, publish_replay_info, serve_sim_proc
from egosim.bridge.scene.objects import publish_object_list
from egosim.msgs import get_profile
from egosim.world import World
from egosim.world.map import build_builtin_map
from egosim.world.scenario import load_default_scenario

PROFILE = get_profile("26.r1")
EGO = PROFILE.message("morai_msgs/EgoVehicleStatus")
OBJECTS = PROFILE.message("morai_msgs/ObjectStatusList")
DT = 0.01


def town_context(data_root: Path) -> BridgeContext:
    world = World(build_builtin_map("town"), load_default_scenario(), physics_step_s=DT)
    return simulation_context(world, data_roots=(data_root,))


def median_us(samples: list[float]) -> float:
    return statistics.median(samples) * 1e6


def record_town(bag: Path, seconds: float) -> list[float]:
    """The town's ego (50 Hz) and objects (20 Hz) recorded through the tap; tap times, s."""
    context = town_context(bag.parent)
    costs = []
    with TopicRecorder(open_recorder(bag)) as recorder:
        tap = recorder.tap()
        for step in range(1, round(seconds / DT) + 1):
            context.world.step(DT)
            stamp_ns = context.stamp_ns()
            outputs = [("/Ego_topic", EGO, publish_ego_status)] if step % 2 == 0 else []
            if step % 5 == 0:
                outputs.append(("/Object_topic", OBJECTS, publish_object_list))
            for topic, kind, build in outputs:
                data = kind.serialize(build(context))
                start = time.perf_counter()
                tap(topic, kind, data, stamp_ns)
                costs.append(time.perf_counter() - start)
    return costs


def play(context: BridgeContext, name: str) -> None:
    handle = PROFILE.message("morai_msgs/MoraiSimProcHandle").new(
        sim_process_status=1, replay_option=0x0001, rosbag_file_name=name, replay_speed=1
    )
    request = PROFILE.service("morai_msgs/MoraiSimProcSrv").request.new(request=handle)
    assert serve_sim_proc(context, context.row("sim_proc"), request).response.result


def step_costs(context: BridgeContext, steps: int, replaying: bool) -> list[float]:
    costs = []
    for _ in range(steps):
        start = time.perf_counter()
        if replaying:
            advance_replay(context, DT)
        context.world.step(DT)
        costs.append(time.perf_counter() - start)
    return costs


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=20.0, help="simulated time recorded")
    args = parser.parse_args()
    steps = round(args.seconds / DT)
    with tempfile.TemporaryDirectory() as directory:
        root = Path(directory)
        taps = record_town(root / "town.bag", args.seconds)
        print(f"recording tap, per message ({len(taps)} messages): {median_us(taps):.1f} us")

        simulated = step_costs(town_context(root), steps, replaying=False)
        context = town_context(root)
        play(context, "town.bag")
        replayed = step_costs(context, steps, replaying=True)
        print(f"World.step, simulating: {median_us(simulated):.0f} us")
        print(f"advance_replay + World.step, replaying all targets: {median_us(replayed):.0f} us")

        info = [0.0] * 200
        for k in range(len(info)):
            start = time.perf_counter()
            publish_replay_info(context, context.row("replay_info"))
            info[k] = time.perf_counter() - start
        print(f"ReplayInfo build (8 NPCs, 6 pedestrians, 4 obstacles): {median_us(info):.0f} us")


if __name__ == "__main__":
    main()
