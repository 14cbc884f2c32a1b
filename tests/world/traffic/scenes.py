"""Small worlds for the world tests, built from scenario data."""

from __future__ import annotations

from typing import Any

from egosim.world import World
from egosim.world.map import LaneMap, build_builtin_map
from egosim.world.scenario import parse_scenario
from egosim.world.vehicle import ControlCommand, LongitudinalMode

# On the straight map, R1_W_2 runs west on the far side of the road: an ego parked there
# is out of the way of everything driving east.
EGO_OUT_OF_THE_WAY = {"start": {"lane": "R1_W_2", "s": 990.0}}


def world_from(data: dict[str, Any], lane_map: LaneMap | None = None, **options: Any) -> World:
    """The world of scenario `data` on `lane_map`, else on the built-in map it names."""
    if lane_map is None:
        lane_map = build_builtin_map(data["map"])
    return World(lane_map, parse_scenario(data, "test scenario"), **options)


def run(world: World, seconds: float, ego_speed_mps: float | None = None) -> None:
    """Step `seconds` of sim time, holding the ego at a velocity command when given."""
    for _ in range(round(seconds / world.physics_step_s)):
        if ego_speed_mps is not None:
            world.egos[0].vehicle.command(
                ControlCommand(mode=LongitudinalMode.VELOCITY, velocity=ego_speed_mps)
            )
        world.step()
