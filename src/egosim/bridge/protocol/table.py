"""The MORAI protocol as data: every topic and service egosim offers.

One row per entry of MORAI SIM's Network Settings tabs. The network settings
file (`--network`) overrides names, rates and on/off per row; nothing else
in egosim hard-codes a topic or service name.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum


class Direction(Enum):
    PUBLISH = "sim->user"
    SUBSCRIBE = "user->sim"
    SERVICE = "service"


@dataclass(frozen=True)
class Row:
    key: str  # stable identifier used by the network settings file
    morai_name: str  # the name MORAI SIM's Network Settings shows for it
    type_name: str  # message type, or service type for services
    direction: Direction
    name: str  # default topic or service name
    rate_hz: float | None = None  # publishers only; None publishes on change
    enabled: bool = True


P, S, V = Direction.PUBLISH, Direction.SUBSCRIBE, Direction.SERVICE

# The ego command inputs MORAI's "Cmd Control" drop-down chooses between; exactly one is live.
EGO_INPUT_ROWS: dict[str, str] = {
    "MoraiCmdController": "ctrl_cmd",
    "WeBOTCmdController": "webot_cmd",
    "GVDirectCmd": "gv_direct_cmd",
    "GVStateCmd": "gv_state_cmd",
    "GhostCtrlCmd": "ghost_ctrl_cmd",
}
DEFAULT_EGO_INPUT = "MoraiCmdController"
DEFAULT_CAMERA_TOPIC = "/image_jpeg/compressed"
DEPTH_TOPIC = "/image"
"""MORAI's default topic of a depth camera (sensor_msgs/Image); the camera row's is a
colour camera's."""

ROWS: tuple[Row, ...] = (
    # Ego network: command inputs (user -> sim)
    Row("ctrl_cmd", "MoraiCmdController", "morai_msgs/CtrlCmd", S, "/ctrl_cmd"),
    Row("webot_cmd", "WeBOTCmdController", "geometry_msgs/Twist", S, "/commands/vel"),
    Row("gv_direct_cmd", "GVDirectCmd", "morai_msgs/GVDirectCmd", S, "/gv_direct_cmd"),
    Row("gv_state_cmd", "GVStateCmd", "morai_msgs/GVStateCmd", S, "/gv_state_cmd"),
    Row("ghost_ctrl_cmd", "GhostCtrlCmd", "morai_msgs/GhostMessage", S, "/ghost_ctrl_cmd"),
    # Ego network: publishers (sim -> user)
    Row("ego_status", "MoraiInfoPublisher", "morai_msgs/EgoVehicleStatus", P, "/Ego_topic", 50),
    Row(
        "object_status",
        "MoraiObjectInfoPublisher",
        "morai_msgs/ObjectStatusList",
        P,
        "/Object_topic",
        20,
    ),
    Row("collision", "CollisionDataPublisher", "morai_msgs/CollisionData", P, "/CollisionData", 20),
    Row(
        "ego_status_extended",
        "MoraiInfoPublisherExtended",
        "morai_msgs/EgoVehicleStatusExtended",
        P,
        "/Ego_topic_extended",
        50,
        enabled=False,
    ),
    Row(
        "object_status_extended",
        "MoraiObjectInfoPublisherExtended",
        "morai_msgs/ObjectStatusListExtended",
        P,
        "/Object_topic_extended",
        20,
        enabled=False,
    ),
    Row(
        "traffic_light_status",
        "TLStatusPublisher",
        "morai_msgs/GetTrafficLightStatus",
        P,
        "/GetTrafficLightStatus",
        10,
    ),
    Row(
        "intersection_status",
        "IntersectionStatusPublisher",
        "morai_msgs/IntersectionStatus",
        P,
        "/InsnStatus",
        10,
    ),
    Row(
        "replay_info",
        "MoraiReplayInfoPublisher",
        "morai_msgs/ReplayInfo",
        P,
        "/ReplayInfo_topic",
        50,
    ),
    Row(
        "sim_proc_status",
        "MoraiSimProcStatusPublisher",
        "morai_msgs/MoraiSimProcStatus",
        P,
        "/sim/process/state/msg/MoraiSimProcStatus",
        10,
    ),
    Row(
        "vehicle_collision",
        "VehicleCollisionInfoPublisher",
        "morai_msgs/VehicleCollisionData",
        P,
        "/VehicleCollisionData",
        20,
    ),
    # Ego / simulator network: subscribers (user -> sim)
    Row("npc_ghost", "NpcGhostCmd", "morai_msgs/NpcGhostCmd", S, "/NpcGhost_Topic"),
    Row(
        "set_traffic_light", "TLCtrlSubscriber", "morai_msgs/SetTrafficLight", S, "/SetTrafficLight"
    ),
    Row(
        "intersection_control",
        "IntersectionControlSubscriber",
        "morai_msgs/IntersectionControl",
        S,
        "/InsnControl",
    ),
    Row("scenario_load", "MORAISLSubscriber", "morai_msgs/ScenarioLoad", S, "/ScenarioLoad"),
    Row(
        "save_sensor_data",
        "SensorSyncDataSubscriber",
        "morai_msgs/SaveSensorData",
        S,
        "/SaveSensorData",
    ),
    Row("lamps", "Lamps", "morai_msgs/Lamps", S, "/lamps"),
    Row(
        "sensor_pos_control",
        "SensorPoseSubscriber",
        "morai_msgs/SensorPosControl",
        S,
        "/SensorPosControl",
    ),
    Row(
        "multi_ego_setting",
        "MultiEgoTransformHandler",
        "morai_msgs/MultiEgoSetting",
        S,
        "/ego_setting",
    ),
    # Sensors of the main ego (sim -> user); mounts and noise in the network settings' sensors:
    Row("gps", "GPS", "morai_msgs/GPSMessage", P, "/gps", 10),
    Row("imu", "IMU", "sensor_msgs/Imu", P, "/imu", 100),
    Row("lidar", "3D LiDAR", "sensor_msgs/PointCloud2", P, "/lidar3D", 10),
    # Every camera of the sensors: section (one topic per distinct name, see camera_rows)
    Row("camera", "Camera", "sensor_msgs/CompressedImage", P, DEFAULT_CAMERA_TOPIC, 30),
    Row("radar", "Radar", "morai_msgs/RadarDetections", P, "/radar", 20),
    Row("tf", "TF2Publisher", "tf2_msgs/TFMessage", P, "/tf", 50),
    # The scene for RViz (an egosim row, not MORAI's): the map latched, then what moves
    Row("markers", "EgosimMarkers", "visualization_msgs/MarkerArray", P, "/egosim/markers", 10),
    # Simulation time (--clock sim / sync); no rate: after every step
    Row("clock", "Clock", "rosgraph_msgs/Clock", P, "/clock"),
    Row("sync_mode_info", "SyncModeInfoPublisher", "morai_msgs/SyncModeInfo", P, "/SyncModeInfo"),
    # Services
    Row(
        "event_cmd",
        "MoraiEventCmdServiceProvider",
        "morai_msgs/MoraiEventCmdSrv",
        V,
        "/Service_MoraiEventCmd",
    ),
    Row(
        "map_spec",
        "MoraiMapSpecServiceProvider",
        "morai_msgs/MoraiMapSpecSrv",
        V,
        "/Service_MoraiMapSpec",
    ),
    Row(
        "scenario_load_srv",
        "MoraiSLServiceProvider",
        "morai_msgs/MoraiScenarioLoadSrv",
        V,
        "/Service_MoraiSL",
    ),
    Row(
        "sim_proc", "MoraiSimProcServiceProvider", "morai_msgs/MoraiSimProcSrv", V, "/Morai_SimProc"
    ),
    Row("tl_info", "MoraiTLInfoServiceProvider", "morai_msgs/MoraiTLInfoSrv", V, "/Morai_TLSrv"),
    Row(
        "vehicle_spec",
        "MoraiVehicleSpecServiceProvider",
        "morai_msgs/MoraiVehicleSpecSrv",
        V,
        "/Service_MoraiVehicleSpec",
    ),
    # Synchronous mode (--clock sync)
    Row(
        "sync_mode_cmd",
        "SyncModeCmdServiceProvider",
        "morai_msgs/MoraiSyncModeCmdSrv",
        V,
        "/SyncModeCmd",
    ),
    Row(
        "sync_mode_wait_for_tick",
        "SyncModeWaitForTickServiceProvider",
        "morai_msgs/MoraiWaitForTickSrv",
        V,
        "/SyncModeWaitForTick",
    ),
    Row(
        "sync_mode_ctrl_cmd",
        "SyncModeCtrlCmdServiceProvider",
        "morai_msgs/MoraiSyncModeCtrlCmdSrv",
        V,
        "/SyncModeCtrlCmd",
    ),
    Row(
        "sync_mode_set_gear",
        "SyncModeSetGearServiceProvider",
        "morai_msgs/MoraiSyncModeSetGearSrv",
        V,
        "/SyncModeSetGear",
    ),
    Row(
        "sync_mode_scenario_load",
        "SyncModeMoraiSLServiceProvider",
        "morai_msgs/MoraiSyncModeSLSrv",
        V,
        "/SyncModeScenarioLoad",
    ),
    Row(
        "sync_mode_add_object",
        "SyncModeAddObjectServiceProvider",
        "morai_msgs/MoraiSyncModeAddObjectSrv",
        V,
        "/SyncModeAddObject",
    ),
    Row(
        "sync_mode_remove_object",
        "SyncModeRemoveObjectServiceProvider",
        "morai_msgs/MoraiSyncModeRemoveObjectSrv",
        V,
        "/SyncModeRemoveObject",
    ),
)

ROWS_BY_KEY: dict[str, Row] = {row.key: row for row in ROWS}
