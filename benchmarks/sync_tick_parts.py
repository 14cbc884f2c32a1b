"""Where a sync-mode tick's time goes, in-process: the simulator's own tick pipeline
(replay, autopilots, world, clock, publish) on the town with its default scenario and
the default network settings, each stage timed, and each published row's building and
serialising timed within the publish stage. The bridge is bound to a real node (on an
embedded master at a free loopback port) with a recording tap, so every row is built
and serialised as if it had a subscriber; nothing is sent (benchmarks/sync_mode.py
measures sending). A second run times the parts of `World.step` (each wrapped in a
timer, about 0.2 us each of overhead) on a fresh world: the same, or with --crowded N
benchmarks/world_step.py's town of N NPCs and 200 pedestrians.

Usage: .venv/bin/python benchmarks/sync_tick_parts.py [--ticks 2000] [--warmup 200]
       [--crowded NPCS]
"""

from __future__ import annotations

import argparse
import time
from collections.abc import Callable
from pathlib import Path

from loopback import free_port
from world_step import crowded_town

from egosim.app.inbox import Inbox
from egosim.app.options import RunOptions
from egosim.app.runner import build_world
from egosim.bridge import (
    HANDLERS,
    Bridge,
    BridgeContext,
    ClockMode,
    Stage,
    Tick,
    TickPipeline,
    default_network_settings,
    simulation_context,
)
from egosim.msgs import MessageType
from egosim.ros1 import Node
from egosim.world import World
from egosim.world.map import build_builtin_map
from egosim.world.populations import base as populations_base
from egosim.world.scenario import parse_scenario

TICK_S = 0.01


def world_parts(world: World) -> dict[str, tuple[object, str]]:
    """The calls `World.step` makes, by what they do: (owner, attribute name)."""
    return {
        "signal programs": (world.signals, "step"),
        "road surface under the ego": (world._simulated_egos, "road_surfaces"),
        "ego dynamics": (world.egos[0].vehicle, "step"),
        "lane projection and occupants": (populations_base, "place_on_lanes"),
        "NPC step": (world.npcs, "step"),
        "pedestrian step": (world.pedestrians, "step"),
        "collisions and contact response": (world._contacts, "step"),
    }


CROWD_PEDESTRIANS = 200


def fresh_world(crowded_npcs: int | None) -> World:
    """The simulator's own world in sync mode, or the crowded town of world_step.py."""
    if crowded_npcs is None:
        return build_world(RunOptions(clock=ClockMode.SYNC))
    town = build_builtin_map("town")
    scenario = crowded_town(town, crowded_npcs, CROWD_PEDESTRIANS)
    return World(town, parse_scenario(scenario, "benchmark"))


def time_world_parts(ticks: int, warmup: int, crowded_npcs: int | None) -> None:
    world = fresh_world(crowded_npcs)
    parts = world_parts(world)
    spent = dict.fromkeys(parts, 0.0)
    for label, (owner, name) in parts.items():
        setattr(owner, name, timed(getattr(owner, name), label, spent))
    for _ in range(warmup):
        world.step(TICK_S)
    spent.update(dict.fromkeys(spent, 0.0))
    began = time.perf_counter()
    for _ in range(ticks):
        world.step(TICK_S)
    whole = time.perf_counter() - began
    print(f"{'World.step, parts timed':44s} {whole / ticks * 1e6:8.0f} us per tick")
    for label, seconds in spent.items():
        print(f"  {label:42s} {seconds / ticks * 1e6:8.0f} us per tick")
    rest = whole - sum(spent.values())
    print(f"  {'the rest (lights view, glue)':42s} {rest / ticks * 1e6:8.0f} us per tick")


def timed(
    call: Callable[..., object], label: str, spent: dict[str, float]
) -> Callable[..., object]:
    def run(*args: object, **kwargs: object) -> object:
        began = time.perf_counter()
        try:
            return call(*args, **kwargs)
        finally:
            spent[label] += time.perf_counter() - began

    return run


def timed_stages(pipeline: TickPipeline[BridgeContext], spent: dict[str, float]) -> None:
    """Wrap every stage of `pipeline` in a timer adding to spent[stage name]."""

    def timed_stage(stage: Stage[BridgeContext]) -> Stage[BridgeContext]:
        def run(context: BridgeContext, tick: Tick) -> None:
            began = time.perf_counter()
            stage.run(context, tick)
            spent[stage.name] += time.perf_counter() - began

        return Stage(stage.name, run)

    pipeline.stages = tuple(timed_stage(stage) for stage in pipeline.stages)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--ticks", type=int, default=2000)
    parser.add_argument("--warmup", type=int, default=200)
    parser.add_argument("--crowded", type=int, metavar="NPCS", default=None)
    args = parser.parse_args()

    world = build_world(RunOptions(clock=ClockMode.SYNC))
    settings = default_network_settings()
    with Node(
        "tick_parts", master_uri=f"http://127.0.0.1:{free_port()}/", rosout_logger=None
    ) as node:
        bridge = Bridge(node, settings, HANDLERS, Inbox())
        context = simulation_context(
            world,
            settings=settings,
            clock_mode=ClockMode.SYNC,
            data_roots=(Path.cwd(),),
            bridge=bridge,
        )
        bridge.open(context)
        built: dict[str, int] = {}

        def count(topic: str, message_type: MessageType, data: bytes, stamp_ns: int) -> None:
            built[topic] = built.get(topic, 0) + 1

        bridge.taps.append(count)  # every row is built as if it had a subscriber
        row_spent = {outlet.row.name: 0.0 for outlet in bridge.outlets}
        for outlet in bridge.outlets:
            outlet.build = timed(outlet.build, outlet.row.name, row_spent)  # type: ignore[assignment]
        stage_spent = dict.fromkeys(context.pipeline.names, 0.0)
        timed_stages(context.pipeline, stage_spent)
        for _ in range(args.warmup):
            context.tick(TICK_S)
        for spent in (stage_spent, row_spent):
            spent.update(dict.fromkeys(spent, 0.0))
        built.clear()
        began = time.perf_counter()
        for _ in range(args.ticks):
            context.tick(TICK_S)
        whole = time.perf_counter() - began

    print(f"town + default scenario, {args.ticks} ticks of {TICK_S * 1000:.0f} ms")
    print(f"{'tick (every stage)':44s} {whole / args.ticks * 1e6:8.0f} us per tick")
    for name, seconds in stage_spent.items():
        print(f"  stage {name:36s} {seconds / args.ticks * 1e6:8.0f} us per tick")
    print("publish stage, building each row (serialising is the rest of the stage):")
    for topic, seconds in row_spent.items():
        if built.get(topic):
            print(
                f"  {topic:42s} {seconds / built[topic] * 1e6:8.0f} us per publish "
                f"{seconds / args.ticks * 1e6:8.1f} us per tick"
            )
    time_world_parts(args.ticks, args.warmup, args.crowded)


if __name__ == "__main__":
    main()
