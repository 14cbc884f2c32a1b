"""Scripted NPC lane changes and stalled NPCs (scenario fields lane_change, stalled)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from egosim.world import World
from egosim.world.map import build_builtin_map
from egosim.world.scenario import parse_scenario

STRAIGHT = build_builtin_map("straight")
AWAY = "ego: {start: {lane: R1_W_2, s: 900}}\n"


def world_with(npcs: str) -> World:
    return World(STRAIGHT, parse_scenario(f"map: straight\n{AWAY}npcs:\n{npcs}"))


def test_lane_change_slides_across_smoothly_turning_its_heading() -> None:
    world = world_with(
        "  - start: {lane: R1_E_1, s: 100}\n"
        "    target_speed_mps: 10\n    speed_mps: 10\n"
        "    lane_change: {lane: R1_E_2, after_s: 1.0, duration_s: 2.0}\n"
    )
    ys, headings = [], []
    for _ in range(200):
        world.step(0.02)
        ys.append(world.npcs.pose[0, 1])
        headings.append(world.npcs.pose[0, 3])
    y, heading = np.array(ys), np.array(headings)
    assert y[:49] == pytest.approx(-1.75)  # in its own lane for the first second
    assert heading[:49] == pytest.approx(0.0)
    # 3.5 m across in 2 s along a half-cosine: half-way at 1 s, fastest there
    # (pi / 2 * 3.5 m / 2 s = 2.75 m/s sideways at 10 m/s: heading -15.4 deg).
    change = 49
    assert y[change + 50] == pytest.approx(-3.5, abs=0.01)
    assert heading[change + 50] == pytest.approx(-math.atan2(math.pi / 2 * 3.5 / 2, 10), abs=1e-3)
    assert np.all(np.diff(y[change : change + 101]) <= 1e-12)
    assert y[-1] == pytest.approx(-5.25) and heading[-1] == pytest.approx(0.0)
    # No jump in heading anywhere: a smooth manoeuvre.
    assert np.max(np.abs(np.diff(heading))) < 0.01
    assert world.map.lane_ids[world.npcs.lane[0]] == "R1_E_2"


def test_a_lane_never_beside_the_npc_is_never_entered() -> None:
    world = world_with(
        "  - start: {lane: R1_E_1, s: 100}\n    speed_mps: 10\n"
        "    lane_change: {lane: R1_W_1, after_s: 0.5}\n"
    )
    for _ in range(100):
        world.step(0.05)
    assert world.map.lane_ids[world.npcs.lane[0]] == "R1_E_1"
    assert world.npcs.pose[0, 1] == pytest.approx(-1.75)


def test_a_stalled_npc_stands_still_and_traffic_queues_behind_it() -> None:
    world = world_with(
        "  - {start: {lane: R1_E_1, s: 300}, speed_mps: 20, stalled: true}\n"
        "  - {start: {lane: R1_E_1, s: 200}, speed_mps: 20}\n"
    )
    for _ in range(60 * 10):
        world.step(0.1)
    assert world.npcs.s[0] == 300.0 and world.npcs.speed[0] == 0.0
    assert world.npcs.speed[1] == pytest.approx(0.0, abs=1e-3)
    assert 295.0 - world.npcs.dims[0, 0] < world.npcs.s[1] < 300.0 - world.npcs.dims[0, 0]
    assert world.vehicle_collisions == []


def test_removing_an_npc_keeps_the_others_lane_changes() -> None:
    world = world_with(
        "  - {start: {lane: R1_E_2, s: 50}}\n"
        "  - start: {lane: R1_E_1, s: 100}\n"
        "    lane_change: {lane: R1_E_2, after_s: 1.0}\n"
    )
    world.npcs.remove([0])
    for _ in range(100):
        world.step(0.05)
    assert world.map.lane_ids[world.npcs.lane[0]] == "R1_E_2"
