"""The ego autopilot (ctrl_mode auto): lane following, speed limit, red lights, dead ends."""

from __future__ import annotations

import pytest
from tests.world.traffic.scenes import world_from

from egosim.world import World
from egosim.world.signals import GREEN, RED
from egosim.world.traffic import LightsView
from egosim.world.traffic.autopilot import STOP_MARGIN_M, LaneAutopilot
from egosim.world.traffic.road_users import lane_occupants_of

# R5_E_1 runs east from junction 6 to junction 7, whose light TL7_W governs it.
APPROACH, LIGHT = "R5_E_1", "TL7_W"


def _drive(world: World, autopilot: LaneAutopilot, seconds: float) -> list[tuple[float, float]]:
    """Step under the autopilot; (speed m/s, |lateral offset| m) after every step."""
    ego = world.egos[0]
    trace = []
    for _ in range(round(seconds / world.physics_step_s)):
        lights = LightsView.of(world.signals)
        others = lane_occupants_of(world.objects(), world.map, but=ego.unique_id)
        command = autopilot.command(ego.vehicle.model, ego.vehicle.status(), lights, others)
        ego.vehicle.command(command)
        world.step()
        trace.append((ego.vehicle.status().speed, abs(world.ego_lane_state().lateral_offset)))
    return trace


def _front_station(world: World) -> float:
    model = world.egos[0].vehicle.model
    return world.ego_lane_state().s + model.cg_to_front_axle + model.front_overhang


def test_cruises_at_the_speed_limit_on_the_lane_centre_and_stops_before_a_dead_end() -> None:
    world = world_from({"map": "straight", "ego": {"start": {"lane": "R1_E_1", "s": 5.0}}})
    limit = world.map.lanes["R1_E_1"].speed_limit
    trace = _drive(world, LaneAutopilot(world.npcs.graph), 80.0)
    assert max(speed for speed, _ in trace) == pytest.approx(limit, abs=0.5)
    assert max(offset for _, offset in trace) < 0.2
    assert trace[-1][0] == pytest.approx(0.0, abs=0.05)
    end = world.map.lanes["R1_E_1"].length
    assert end - STOP_MARGIN_M - 1.5 < _front_station(world) <= end


def test_follows_the_bends_of_the_loop() -> None:
    world = world_from({"map": "loop", "ego": {"start": {"lane": "R1_N_1", "s": 0.0}}})
    trace = _drive(world, LaneAutopilot(world.npcs.graph), 60.0)
    assert min(speed for speed, _ in trace[-1000:]) > 5.0
    # The whole body stays inside its lane.
    room = (world.map.lanes["R1_N_1"].widths[0] - world.egos[0].vehicle.model.width) / 2.0
    assert max(offset for _, offset in trace) < room


def test_stops_before_the_stop_line_on_red_and_goes_on_green() -> None:
    world = world_from({"map": "town", "ego": {"start": {"lane": APPROACH, "s": 10.0}}})
    world.signals.set_light(LIGHT, RED)
    autopilot = LaneAutopilot(world.npcs.graph)
    trace = _drive(world, autopilot, 40.0)
    stop_line = world.map.lanes[APPROACH].stop_line_s
    assert world.ego_lane_state().lane_id == APPROACH
    assert trace[-1][0] == pytest.approx(0.0, abs=0.05)
    assert stop_line - STOP_MARGIN_M - 1.5 < _front_station(world) <= stop_line

    world.signals.set_light(LIGHT, GREEN)
    _drive(world, autopilot, 15.0)
    assert world.ego_lane_state().lane_id != APPROACH


def test_stops_behind_a_parked_car_and_follows_a_slower_one() -> None:
    parked = {"start": {"lane": "R1_E_1", "s": 300.0}, "start_delay_s": 1.0e6}
    world = world_from(
        {"map": "straight", "ego": {"start": {"lane": "R1_E_1", "s": 5.0}}, "npcs": [parked]}
    )
    autopilot = LaneAutopilot(world.npcs.graph)
    trace = _drive(world, autopilot, 40.0)
    gap = world.npcs.s[0] - world.npcs.dims[0, 0] / 2.0 - _front_station(world)
    assert trace[-1][0] == pytest.approx(0.0, abs=0.05)
    assert 0.5 * autopilot.idm.min_gap_m < gap < autopilot.idm.min_gap_m + 1.0
    assert world.ego_collision_log == []

    slower = {"start": {"lane": "R1_E_1", "s": 100.0}, "speed_mps": 10.0, "target_speed_mps": 10.0}
    world = world_from(
        {"map": "straight", "ego": {"start": {"lane": "R1_E_1", "s": 5.0}}, "npcs": [slower]}
    )
    trace = _drive(world, LaneAutopilot(world.npcs.graph), 40.0)
    assert trace[-1][0] == pytest.approx(10.0, abs=0.3)
    assert world.ego_collision_log == []
