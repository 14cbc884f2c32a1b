"""A ground vehicle model in a scenario makes the world's ego a skid-steer."""

from __future__ import annotations

import math

import pytest

from egosim.world import World
from egosim.world.map import build_builtin_map
from egosim.world.scenario import ScenarioError, parse_scenario
from egosim.world.vehicle import (
    GROUND_VEHICLE_CATALOGUE,
    BodyVelocityCommand,
    Pose,
    SkidSteerVehicle,
    UnknownVehicleModelError,
    Vehicle,
)

STRAIGHT = build_builtin_map("straight")


def scenario(model: str) -> str:
    return f"map: straight\nego:\n  model: {model}\n  start: {{lane: R1_E_1, s: 10.0}}\n"


def test_a_ground_vehicle_scenario_gives_a_skid_steer_ego_of_its_size() -> None:
    world = World(STRAIGHT, parse_scenario(scenario("UGV_6W_Skid_Steer")))
    vehicle = world.egos[0].vehicle
    assert isinstance(vehicle, SkidSteerVehicle)
    model = GROUND_VEHICLE_CATALOGUE["UGV_6W_Skid_Steer"]
    table = world.objects()
    assert table.names[0] == "UGV_6W_Skid_Steer"
    assert tuple(table.sizes[0]) == (model.length, model.width, model.height)


def test_the_world_steps_a_skid_steer_ego_along_its_commands() -> None:
    world = World(STRAIGHT, parse_scenario(scenario("WeBOT_Indoor_Robot")))
    start = world.ego_status().pose
    for _ in range(300):
        world.egos[0].vehicle.command(BodyVelocityCommand(linear=1.0, angular=0.2))
        world.step()
    status = world.ego_status()
    assert status.velocity[0] == pytest.approx(1.0, abs=1e-3)
    assert status.yaw_rate == pytest.approx(0.2, abs=1e-3)
    assert math.remainder(status.pose.yaw - start.yaw, math.tau) > 0.0


def test_loading_a_car_scenario_after_a_robot_makes_the_ego_a_car_again() -> None:
    world = World(STRAIGHT, parse_scenario(scenario("WeBOT_Indoor_Robot")))
    world.load_scenario(parse_scenario(scenario("2016_Kia_Niro(HEV)")))
    assert isinstance(world.egos[0].vehicle, Vehicle)


def test_add_ego_chooses_the_kind_by_model() -> None:
    world = World(STRAIGHT)
    robot = world.add_ego("WeBOT_Indoor_Robot", Pose(x=50.0, y=-1.75))
    assert isinstance(robot.vehicle, SkidSteerVehicle)
    with pytest.raises(UnknownVehicleModelError, match="UGV_6W_Skid_Steer"):
        world.add_ego("Hovercraft", Pose())


def test_an_unknown_ego_model_names_the_ground_vehicles_too() -> None:
    with pytest.raises(ScenarioError, match="WeBOT_Indoor_Robot") as error:
        World(STRAIGHT, parse_scenario(scenario("Hovercraft"), "robot.yaml"))
    assert "robot.yaml" in str(error.value)
