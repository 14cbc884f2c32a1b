"""The living world around the ego: NPC vehicles, pedestrians, static obstacles.

Public API:
    NpcFleet, NpcSpawn, IntelligentDriverModel     vectorised IDM lane followers
    PedestrianCrowd, PedestrianSpawn, WalkPath     walkers on sidewalks / crosswalks / waypoints
    StaticObstacles, ObstacleSpawn                 boxes standing still
    ObjectType, ObjectState, ObjectTable           ObjectStatus semantics (SI units)
    ObjectList, NearestObjects, closest_objects    ObjectStatusList semantics
    SceneObjects                                   every object, with its rows per kind
    LaneGraph, LaneOccupants, LightsView           the arrays the agents run on
    BoxModel, PEDESTRIAN_MODELS, OBSTACLE_MODELS   sizes of non-vehicle models
    MORAI_OBSTACLE_DATA_IDS, obstacle_for_data_id  MORAI's obstacle DataIDs -> models
"""

from egosim.world.traffic.catalogue import (
    DEFAULT_OBSTACLE_MODEL,
    DEFAULT_PEDESTRIAN_MODEL,
    MORAI_OBSTACLE_DATA_IDS,
    OBSTACLE_MODELS,
    PEDESTRIAN_MODELS,
    BoxModel,
    obstacle_for_data_id,
)
from egosim.world.traffic.idm import IntelligentDriverModel
from egosim.world.traffic.lane_graph import LaneGraph
from egosim.world.traffic.leaders import LaneOccupants, leaders_ahead
from egosim.world.traffic.npc_vehicles import NpcFleet, NpcSpawn
from egosim.world.traffic.object_list import (
    NearestObjects,
    ObjectList,
    SceneObjects,
    closest_objects,
)
from egosim.world.traffic.objects import ObjectState, ObjectTable, ObjectType
from egosim.world.traffic.obstacles import ObstacleSpawn, StaticObstacles
from egosim.world.traffic.pedestrians import (
    CrosswalkLights,
    PedestrianCrowd,
    PedestrianSpawn,
    WalkPath,
    crossed_lights,
    crosswalk_path,
    sidewalk_path,
)
from egosim.world.traffic.signal_rules import LightsView, signal_permissions

__all__ = [
    "DEFAULT_OBSTACLE_MODEL",
    "DEFAULT_PEDESTRIAN_MODEL",
    "MORAI_OBSTACLE_DATA_IDS",
    "OBSTACLE_MODELS",
    "PEDESTRIAN_MODELS",
    "BoxModel",
    "CrosswalkLights",
    "IntelligentDriverModel",
    "LaneGraph",
    "LaneOccupants",
    "LightsView",
    "NearestObjects",
    "NpcFleet",
    "NpcSpawn",
    "ObjectList",
    "ObjectState",
    "ObjectTable",
    "ObjectType",
    "ObstacleSpawn",
    "PedestrianCrowd",
    "PedestrianSpawn",
    "SceneObjects",
    "StaticObstacles",
    "WalkPath",
    "closest_objects",
    "crossed_lights",
    "crosswalk_path",
    "leaders_ahead",
    "obstacle_for_data_id",
    "sidewalk_path",
    "signal_permissions",
]
