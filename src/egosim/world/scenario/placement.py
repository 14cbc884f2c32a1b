"""Scenario entries placed on a map: the spawns the traffic modules take.

Errors (unknown lanes, sidewalks, models ...) name the scenario's file, line and field.
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from typing import TypeVar

import numpy as np

from egosim.world.map import LaneMap
from egosim.world.scenario.model import LaneStart, PoseStart, Scenario, Start
from egosim.world.traffic.catalogue import OBSTACLE_MODELS, PEDESTRIAN_MODELS, BoxModel
from egosim.world.traffic.npc_vehicles import NpcSpawn
from egosim.world.traffic.obstacles import ObstacleSpawn
from egosim.world.traffic.pedestrians import (
    PedestrianSpawn,
    WalkPath,
    crosswalk_path,
    sidewalk_path,
)
from egosim.world.vehicle import EGO_MODELS, VEHICLE_CATALOGUE, EgoModel
from egosim.world.vehicle import Pose as VehiclePose
from egosim.yamltext import FieldPath

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
    for npc in scenario.npcs:
        model = vehicle_model_at(scenario, npc.model, (*npc.path, "model"), VEHICLE_CATALOGUE)
        lane, s, lateral = lane_position(scenario, lane_map, npc.start, (*npc.path, "start"))
        route = tuple(
            _lane_index(scenario, lane_map, lane_id, (*npc.path, "route", k))
            for k, lane_id in enumerate(npc.route)
        )
        spawns.append(
            NpcSpawn(
                unique_id=next(ids),
                model=model,
                lane=lane,
                s=s,
                lateral=lateral,
                speed=npc.speed,
                target_speed=npc.target_speed,
                speed_factor=npc.speed_factor,
                route=route,
                start_delay_s=npc.start_delay_s,
            )
        )
    return spawns


def pedestrian_spawns(
    scenario: Scenario, lane_map: LaneMap, ids: Iterator[int]
) -> list[PedestrianSpawn]:
    crosswalk_index = {cw: k for k, cw in enumerate(lane_map.crosswalks)}
    spawns = []
    for walker in scenario.pedestrians:
        model = _box_model(scenario, PEDESTRIAN_MODELS, walker.model, (*walker.path, "model"))
        path: WalkPath
        if walker.sidewalk is not None:
            if walker.sidewalk not in lane_map.sidewalks:
                raise scenario.error(
                    (*walker.path, "sidewalk"), f"no sidewalk {walker.sidewalk!r} in the map"
                )
            path = sidewalk_path(lane_map.sidewalks[walker.sidewalk])
        elif walker.crosswalk is not None:
            if walker.crosswalk not in lane_map.crosswalks:
                raise scenario.error(
                    (*walker.path, "crosswalk"), f"no crosswalk {walker.crosswalk!r} in the map"
                )
            path = crosswalk_path(
                lane_map.crosswalks[walker.crosswalk], crosswalk_index[walker.crosswalk]
            )
        else:
            path = WalkPath(np.array(walker.waypoints, dtype=np.float64), closed=walker.loop)
        if walker.start_s > path.length:
            raise scenario.error(
                (*walker.path, "start_s"),
                f"{walker.start_s} m is past the path's {path.length:.1f} m",
            )
        spawns.append(PedestrianSpawn(next(ids), model, path, walker.speed, walker.start_s))
    return spawns


def obstacle_spawns(scenario: Scenario, ids: Iterator[int]) -> list[ObstacleSpawn]:
    spawns = []
    for obstacle in scenario.obstacles:
        size = obstacle.size
        if size is None:
            model = _box_model(scenario, OBSTACLE_MODELS, obstacle.model, (*obstacle.path, "model"))
            size = (model.length, model.width, model.height)
        pose = obstacle.pose
        spawns.append(
            ObstacleSpawn(next(ids), obstacle.model, (pose.x, pose.y, pose.z), pose.heading, size)
        )
    return spawns
