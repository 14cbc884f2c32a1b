"""Scenario entries placed on a map: the spawns the traffic modules take.

Errors (unknown lanes, sidewalks, models ...) name the scenario's file, line and field.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Mapping
from typing import TypeVar

import numpy as np

from egosim.world.map import LaneMap
from egosim.world.scenario.model import (
    LaneStart,
    NpcSpec,
    PedestrianSpec,
    PoseStart,
    Scenario,
    Start,
)
from egosim.world.traffic.catalogue import OBSTACLE_MODELS, PEDESTRIAN_MODELS, BoxModel
from egosim.world.traffic.npc_vehicles import LaneChange, NpcSpawn
from egosim.world.traffic.obstacles import ObstacleSpawn
from egosim.world.traffic.pedestrians import (
    PedestrianSpawn,
    WalkPath,
    crosswalk_path,
    sidewalk_path,
)
from egosim.world.vehicle import EGO_MODELS, VEHICLE_CATALOGUE, EgoModel, VehicleModel
from egosim.world.vehicle import Pose as VehiclePose
from egosim.yamltext import FieldPath, Problems

ModelT = TypeVar("ModelT")


def check_map(scenario: Scenario, lane_map: LaneMap) -> None:
    if scenario.map_name != lane_map.name:
        raise scenario.error(
            ("map",), f"scenario is for map {scenario.map_name!r}, the world runs {lane_map.name!r}"
        )


def vehicle_model_at(
    scenario: Scenario,
    name: str,
    path: FieldPath,
    catalogue: Mapping[str, ModelT],
) -> ModelT:
    try:
        return catalogue[name]
    except KeyError:
        known = ", ".join(sorted(catalogue))
        raise scenario.error(path, f"unknown vehicle model {name!r}; known: {known}") from None


def _box_model(
    scenario: Scenario, catalogue: dict[str, BoxModel], name: str, path: FieldPath
) -> BoxModel:
    try:
        return catalogue[name]
    except KeyError:
        known = ", ".join(sorted(catalogue))
        raise scenario.error(path, f"unknown model {name!r}; known: {known}") from None


def _lane_index(scenario: Scenario, lane_map: LaneMap, lane_id: str, path: FieldPath) -> int:
    if lane_id not in lane_map.lanes:
        raise scenario.error(path, f"no lane {lane_id!r} in map {lane_map.name!r}")
    return lane_map.lane_index(lane_id)


def lane_position(
    scenario: Scenario, lane_map: LaneMap, start: Start, path: FieldPath
) -> tuple[int, float, float]:
    """(lane index, station m, lateral m) of a start: a lane start as given, a pose
    projected onto the lane it lies on (its heading preferring lanes that point its way)."""
    if isinstance(start, LaneStart):
        index = _lane_index(scenario, lane_map, start.lane, (*path, "lane"))
        length = lane_map.lane_lengths[index]
        if start.ratio is not None:
            return index, start.ratio * float(length), start.lateral
        if start.s > length:
            raise scenario.error(
                (*path, "s"),
                f"station {start.s} m is past the end of lane {start.lane} ({length:.1f} m)",
            )
        return index, start.s, start.lateral
    projection = lane_map.project(start.x, start.y, start.heading)
    return lane_map.lane_index(projection.lane_id), projection.s, projection.lateral


def world_pose(lane_map: LaneMap, start: Start, path: FieldPath, scenario: Scenario) -> PoseStart:
    """The map pose of a start (a lane start sits on the centreline plus its offset)."""
    if isinstance(start, PoseStart):
        return start
    index, s, lateral = lane_position(scenario, lane_map, start, path)
    x, y, z, heading = lane_map.poses_at(np.array([index]), np.array([s]))[0]
    return PoseStart(
        float(x - lateral * np.sin(heading)),
        float(y + lateral * np.cos(heading)),
        float(z),
        float(heading),
    )


def ego_placement(
    scenario: Scenario, lane_map: LaneMap
) -> tuple[EgoModel, VehiclePose, float] | None:
    """Model, pose (of the vehicle's reference point) and speed (m/s) of the scenario's
    ego; None when the scenario has no ego section."""
    ego = scenario.ego
    if ego is None:
        return None
    model = vehicle_model_at(scenario, ego.model, (*ego.path, "model"), EGO_MODELS)
    pose = world_pose(lane_map, ego.start, (*ego.path, "start"), scenario)
    return model, VehiclePose(x=pose.x, y=pose.y, z=pose.z, yaw=pose.heading), ego.speed


def npc_spawns(scenario: Scenario, lane_map: LaneMap, ids: Iterator[int]) -> list[NpcSpawn]:
    spawns = []
    problems = Problems()
    for npc in scenario.npcs:
        with problems.collecting():
            spawns.append(_npc_spawn(scenario, lane_map, npc, next(ids)))
    problems.raise_any()
    return spawns


def _npc_spawn(scenario: Scenario, lane_map: LaneMap, npc: NpcSpec, unique_id: int) -> NpcSpawn:
    problems = Problems()
    model: VehicleModel | None = None
    position: tuple[int, float, float] | None = None
    change: LaneChange | None = None
    route: list[int] = []
    with problems.collecting():
        model = vehicle_model_at(scenario, npc.model, (*npc.path, "model"), VEHICLE_CATALOGUE)
    with problems.collecting():
        position = lane_position(scenario, lane_map, npc.start, (*npc.path, "start"))
    for k, lane_id in enumerate(npc.route):
        with problems.collecting():
            route.append(_lane_index(scenario, lane_map, lane_id, (*npc.path, "route", k)))
    if npc.lane_change is not None:
        with problems.collecting():
            target = _lane_index(
                scenario, lane_map, npc.lane_change.lane, (*npc.path, "lane_change", "lane")
            )
            change = LaneChange(target, npc.lane_change.after_s, npc.lane_change.duration_s)
    problems.raise_any()
    assert model is not None and position is not None
    lane, s, lateral = position
    return NpcSpawn(
        unique_id=unique_id,
        model=model,
        lane=lane,
        s=s,
        lateral=lateral,
        speed=0.0 if npc.stalled else npc.speed,
        target_speed=npc.target_speed,
        speed_factor=npc.speed_factor,
        route=tuple(route),
        start_delay_s=math.inf if npc.stalled else npc.start_delay_s,
        lane_change=change,
        active_distance=math.inf if npc.active_distance is None else npc.active_distance,
    )


def pedestrian_spawns(
    scenario: Scenario, lane_map: LaneMap, ids: Iterator[int]
) -> list[PedestrianSpawn]:
    spawns = []
    problems = Problems()
    for walker in scenario.pedestrians:
        with problems.collecting():
            spawns.append(_pedestrian_spawn(scenario, lane_map, walker, next(ids)))
    problems.raise_any()
    return spawns


def _pedestrian_spawn(
    scenario: Scenario, lane_map: LaneMap, walker: PedestrianSpec, unique_id: int
) -> PedestrianSpawn:
    problems = Problems()
    model = None
    with problems.collecting():
        model = _box_model(scenario, PEDESTRIAN_MODELS, walker.model, (*walker.path, "model"))
    path = _walk_path(scenario, lane_map, walker)
    if walker.start_s > path.length:
        problems.add(
            scenario.error(
                (*walker.path, "start_s"),
                f"{walker.start_s} m is past the path's {path.length:.1f} m",
            )
        )
    problems.raise_any()
    assert model is not None
    return PedestrianSpawn(
        unique_id,
        model,
        path,
        walker.speed,
        walker.start_s,
        active_distance=math.inf if walker.active_distance is None else walker.active_distance,
        wake_point=walker.wake_point,
    )


def _walk_path(scenario: Scenario, lane_map: LaneMap, walker: PedestrianSpec) -> WalkPath:
    if walker.sidewalk is not None:
        if walker.sidewalk not in lane_map.sidewalks:
            raise scenario.error(
                (*walker.path, "sidewalk"), f"no sidewalk {walker.sidewalk!r} in the map"
            )
        return sidewalk_path(lane_map.sidewalks[walker.sidewalk])
    if walker.crosswalk is not None:
        if walker.crosswalk not in lane_map.crosswalks:
            raise scenario.error(
                (*walker.path, "crosswalk"), f"no crosswalk {walker.crosswalk!r} in the map"
            )
        index = list(lane_map.crosswalks).index(walker.crosswalk)
        return crosswalk_path(lane_map.crosswalks[walker.crosswalk], index)
    return WalkPath(np.array(walker.waypoints, dtype=np.float64), closed=walker.loop)


def obstacle_spawns(scenario: Scenario, ids: Iterator[int]) -> list[ObstacleSpawn]:
    spawns = []
    problems = Problems()
    for obstacle in scenario.obstacles:
        size = obstacle.size
        if size is None:
            with problems.collecting():
                model = _box_model(
                    scenario, OBSTACLE_MODELS, obstacle.model, (*obstacle.path, "model")
                )
                size = (model.length, model.width, model.height)
        pose = obstacle.pose
        if size is not None:
            spawns.append(
                ObstacleSpawn(
                    next(ids), obstacle.model, (pose.x, pose.y, pose.z), pose.heading, size
                )
            )
    problems.raise_any()
    return spawns
