"""Scripted drives: the main ego is held on a prescribed path and the evaluator watches."""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

from egosim.evaluation import DriveEvaluator
from egosim.world import World
from egosim.world.vehicle import Pose

DT = 0.01

# (x, y, yaw, speed) of the ego at time t.
Script = Callable[[float], tuple[float, float, float, float]]


def straight(x0: float, y: float, speed: float, yaw: float = 0.0) -> Script:
    return lambda t: (x0 + speed * t * math.cos(yaw), y + speed * t * math.sin(yaw), yaw, speed)


def along_lane(world: World, lane_id: str, s0: float, speed: float) -> Script:
    return along_lanes(world, (lane_id,), s0, speed)


def along_lanes(world: World, lane_ids: Sequence[str], s0: float, speed: float) -> Script:
    """On the centre lines of `lane_ids` driven one after the other, from station s0 of the
    first at `speed`; held at the last one's end."""
    lengths = [world.map.lanes[i].length for i in lane_ids]

    def at(t: float) -> tuple[float, float, float, float]:
        s, k = s0 + speed * t, 0
        while k < len(lane_ids) - 1 and s > lengths[k]:
            s, k = s - lengths[k], k + 1
        x, y, _, heading = world.map.pose_at(lane_ids[k], s)
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


def sample_exactly(
    world: World, evaluator: DriveEvaluator, script: Script, duration_s: float, period_s: float
) -> None:
    """Step the world `period_s` at a time (a sync client's tick) and show the evaluator the
    ego exactly where `script` has it at each sample's time, from t = 0 to `duration_s`."""

    def place() -> None:
        x, y, yaw, speed = script(world.sim_time)
        world.egos[0].vehicle.teleport(Pose(x=x, y=y, yaw=yaw), speed)

    place()
    evaluator.observe(world)
    for _ in range(math.ceil(duration_s / period_s - 1e-9)):
        world.step(period_s)
        place()
        evaluator.observe(world)
