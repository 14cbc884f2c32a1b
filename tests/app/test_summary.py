"""The summary `egosim run` prints beside `egosim: ready` tells what runs and what to try."""

from __future__ import annotations

import math
from pathlib import Path

from egosim.app.options import ClockMode, RunOptions
from egosim.app.runner import build_world
from egosim.app.summary import ready_summary

EXAMPLES = Path(__file__).parents[2] / "examples"


def test_default_town_summary_names_map_ego_traffic_and_clock() -> None:
    options = RunOptions()
    world = build_world(options)
    lines = ready_summary(world, options).splitlines()
    assert len(lines) == 3
    assert all(line.startswith("egosim: ") for line in lines)
    assert lines[0] == "egosim: map town, scenario the town's default, clock real time"
    pose = world.ego_status().pose
    lane = world.ego_lane_state().lane_id
    heading = math.degrees(pose.yaw)
    assert lines[1] == (
        f"egosim: ego at x={pose.x:.1f} y={pose.y:.1f} m, heading {heading:.1f} deg, "
        f"lane {lane}; {len(world.npcs)} NPCs, {len(world.pedestrians)} pedestrians, "
        f"{len(world.obstacles)} obstacles, {len(world.signals.light_ids)} traffic lights"
    )
    assert len(world.npcs) > 1 and len(world.pedestrians) > 1 and len(world.obstacles) > 1
    assert "rostopic echo -n 1 /Ego_topic" in lines[2]
    assert "egosim msgs --export-python" in lines[2]


def test_scenario_file_and_sim_clock_as_fast_as_possible() -> None:
    scenario = EXAMPLES / "town_lap_scenario.yaml"
    options = RunOptions(scenario=scenario, clock=ClockMode.SIM, rtf=0.0)
    world = build_world(options)
    first = ready_summary(world, options).splitlines()[0]
    assert (
        first
        == f"egosim: map town, scenario {scenario}, clock sim time (/clock) as fast as possible"
    )


def test_sync_mode_suggests_starting_the_steps() -> None:
    options = RunOptions(map="straight", clock=ClockMode.SYNC)
    lines = ready_summary(build_world(options), options).splitlines()
    assert (
        lines[0] == "egosim: map straight, scenario none, clock sync (the client steps the world)"
    )
    assert "0 NPCs, 0 pedestrians, 0 obstacles, 0 traffic lights" in lines[1]
    assert "/SyncModeCmd" in lines[2]
