"""EgoVehicleStatusExtended and ObjectStatusListExtended: every field from the world."""

from __future__ import annotations

import math

import pytest

from egosim.bridge import HANDLERS, simulation_context
from egosim.world import World
from egosim.world.map import build_builtin_map
from egosim.world.scenario import parse_scenario
from egosim.world.traffic.ghosts import GhostPlacement, TurnSignal
from egosim.world.vehicle import ControlCommand, LongitudinalMode, vehicle_model

STRAIGHT = build_builtin_map("straight")
EGO_ALONE = """\
map: straight
ego: {start: {lane: R1_E_1, s: 10.0}}
"""
ONE_NPC = (
    EGO_ALONE
    + """\
npcs:
  - {model: 2019_Hyundai_Sonata, start: {lane: R1_E_1, s: 60.0}}
"""
)


def published(context, key: str):
    return HANDLERS.publishers[key](context, context.row(key))


def test_wheel_speeds_and_rates_of_a_car_on_a_steady_circle() -> None:
    world = World(STRAIGHT, parse_scenario(EGO_ALONE))
    context = simulation_context(world)
    vehicle = world.egos[0].vehicle
    circle = ControlCommand(mode=LongitudinalMode.VELOCITY, velocity=5.0, front_steer=0.1)
    for _ in range(1500):
        vehicle.command(circle)
        context.tick(0.01)
    message = published(context, "ego_status_extended")
    status = world.ego_status()
    model = vehicle.model
    r = status.yaw_rate
    assert message.yaw_rate == pytest.approx(math.degrees(r))
    assert message.wheel_angle == pytest.approx(math.degrees(status.front_steer))
    # Rear wheels are not steered: their speeds are the body's at each side of the axle.
    assert message.RL_wheel_speed + message.RR_wheel_speed == pytest.approx(
        2 * status.velocity[0], rel=1e-6
    )
    assert message.RR_wheel_speed - message.RL_wheel_speed == pytest.approx(
        r * model.track_width,
        rel=1e-6,  # the outer (right) wheel of a left turn is faster
    )
    assert message.FL_wheel_speed > message.RL_wheel_speed  # the front axle sweeps wider


def test_steering_speed_is_the_change_since_the_last_message() -> None:
    world = World(STRAIGHT)
    context = simulation_context(world)
    vehicle = world.egos[0].vehicle
    published(context, "ego_status_extended")
    before = world.ego_status().front_steer
    vehicle.command(ControlCommand(mode=LongitudinalMode.VELOCITY, velocity=0.0, front_steer=0.3))
    for _ in range(10):
        context.tick(0.01)
    message = published(context, "ego_status_extended")
    expected = math.degrees(world.ego_status().front_steer - before) / 0.1
    assert expected > 0.0
    assert message.wheel_angle_speed == pytest.approx(expected)


def test_an_npc_reports_its_lane_and_the_distances_to_its_boundaries() -> None:
    world = World(STRAIGHT, parse_scenario(ONE_NPC))
    context = simulation_context(world)
    context.tick(0.01)
    message = published(context, "object_status_extended")
    (npc,) = message.npc_list
    assert list(npc.global_path_info) == ["R1_E_1"]
    assert npc.lane_departure == 0
    lane_width = 3.5
    assert npc.distance_left_lane + npc.distance_right_lane == pytest.approx(lane_width, abs=1e-6)
    heading = math.radians(npc.heading)
    assert (npc.orientation.z, npc.orientation.w) == pytest.approx(
        (math.sin(heading / 2), math.cos(heading / 2))
    )
    assert npc.object_yaw_rate == 0.0


def test_an_npc_ghost_reports_the_turn_signal_it_was_placed_with() -> None:
    world = World(STRAIGHT, parse_scenario(EGO_ALONE))
    x, y, z, heading = STRAIGHT.pose_at("R1_E_1", 40.0)
    model = vehicle_model("2019_Hyundai_Sonata")
    placements = [
        GhostPlacement(900, model, (x, y, z), heading, turn_signal=TurnSignal.LEFT),
        GhostPlacement(901, model, (x + 20.0, y, z), heading, turn_signal=TurnSignal.HAZARD),
    ]
    assert world.place_npc_ghosts(placements) == []
    context = simulation_context(world)
    context.tick(0.01)
    message = published(context, "object_status_extended")
    signals = {npc.unique_id: npc.turn_signal for npc in message.npc_list}
    assert signals == {900: int(TurnSignal.LEFT), 901: int(TurnSignal.HAZARD)}
