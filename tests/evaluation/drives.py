"""Scripted drives: the main ego is held on a prescribed path and the evaluator watches."""

from __future__ import annotations

import math
from collections.abc import Callable

from egosim.evaluation import DriveEvaluator
from egosim.world import World
from egosim.world.vehicle import Pose

DT = 0.01

# (x, y, yaw, speed) of the ego at time t.
Script = Callable[[float], tuple[float, float, float, float]]


def straight(x0: float, y: float, speed: float, yaw: float = 0.0) -> Script:
    return lambda t: (x0 + speed * t * math.cos(yaw), y + speed * t * math.sin(yaw), yaw, speed)


def along_lane(world: World, lane_id: str, s0: float, speed: float) -> Script:
    def at(t: float) -> tuple[float, float, float, float]:
        x, y, _, heading = world.map.pose_at(lane_id, s0 + speed * t)
        return x, y, heading, speed

    return at


def drive(world: World, evaluator: DriveEvaluator, script: Script, duration_s: float) -> None:
    """Hold the ego on `script` for `duration_s`, stepping the world and the evaluator;
    after a collision the ego is left where the world stopped it."""
    collided = False
    for _ in range(round(duration_s / DT)):
        if not collided:
            x, y, yaw, speed = script(world.sim_time)
            world.egos[0].vehicle.teleport(Pose(x=x, y=y, yaw=yaw), speed)
        world.step(DT)
        evaluator.observe(world)
        collided = collided or bool(world.ego_collision_log)
