"""Which handler serves each row of the protocol table, and the type each one takes."""

from __future__ import annotations

from ..msgs import get_profile
from . import sim_clock
from .core import Handlers
from .egos import ego, events, extended_status, ghost, ground_vehicle, multi_ego
from .receivers import handler, prepared_handler
from .replay import replay_rows
from .scene import lights, markers, objects, scenarios, specs
from .sensors import camera_rows, sensor_files, sensor_rows
from .sync import sync_mode, sync_objects

HANDLERS = Handlers(
    publishers={
        "ego_status": ego.publish_ego_status,
        "ego_status_extended": extended_status.publish_ego_status_extended,
        "object_status_extended": extended_status.publish_object_list_extended,
        "object_status": objects.publish_object_list,
        "collision": objects.publish_collision,
        "vehicle_collision": objects.publish_vehicle_collisions,
        "traffic_light_status": lights.publish_traffic_light_status,
        "intersection_status": lights.publish_intersection_status,
        "gps": sensor_rows.publish_gps,
        "imu": sensor_rows.publish_imu,
        "lidar": sensor_rows.publish_lidar,
        "radar": sensor_rows.publish_radar,
        "tf": sensor_rows.publish_tf,
        "clock": sim_clock.publish_clock,
        "sync_mode_info": sync_mode.publish_sync_mode_info,
        "sim_proc_status": replay_rows.publish_sim_proc_status,
        "replay_info": replay_rows.publish_replay_info,
        "markers": markers.build_scene_markers,
    },
    subscribers={
        "ctrl_cmd": handler(lambda p: p.message("morai_msgs/CtrlCmd"), ego.on_ctrl_cmd),
        "ghost_ctrl_cmd": handler(
            lambda p: p.message("morai_msgs/GhostMessage"), ghost.on_ghost_ctrl_cmd
        ),
        "npc_ghost": handler(lambda p: p.message("morai_msgs/NpcGhostCmd"), ghost.on_npc_ghost),
        "multi_ego_setting": handler(
            lambda p: p.message("morai_msgs/MultiEgoSetting"), multi_ego.on_multi_ego_setting
        ),
        "webot_cmd": handler(
            lambda p: p.message("geometry_msgs/Twist"), ground_vehicle.on_webot_cmd
        ),
        "gv_direct_cmd": handler(
            lambda p: p.message("morai_msgs/GVDirectCmd"), ground_vehicle.on_gv_direct_cmd
        ),
        "gv_state_cmd": handler(
            lambda p: p.message("morai_msgs/GVStateCmd"), ground_vehicle.on_gv_state_cmd
        ),
        "set_traffic_light": handler(
            lambda p: p.message("morai_msgs/SetTrafficLight"), lights.on_set_traffic_light
        ),
        "intersection_control": handler(
            lambda p: p.message("morai_msgs/IntersectionControl"), lights.on_intersection_control
        ),
        "scenario_load": prepared_handler(
            lambda p: p.message("morai_msgs/ScenarioLoad"),
            scenarios.prepare_scenario,
            scenarios.on_scenario_load,
        ),
        "lamps": handler(lambda p: p.message("morai_msgs/Lamps"), events.on_lamps),
        "sensor_pos_control": handler(
            lambda p: p.message("morai_msgs/SensorPosControl"), sensor_rows.on_sensor_pos_control
        ),
        "save_sensor_data": handler(
            lambda p: p.message("morai_msgs/SaveSensorData"), sensor_files.on_save_sensor_data
        ),
    },
    services={
        "event_cmd": handler(
            lambda p: p.message("morai_msgs/MoraiEventCmdSrvRequest"), events.serve_event_cmd
        ),
        "map_spec": handler(
            lambda p: p.message("morai_msgs/MoraiMapSpecSrvRequest"), specs.serve_map_spec
        ),
        "vehicle_spec": handler(
            lambda p: p.message("morai_msgs/MoraiVehicleSpecSrvRequest"), specs.serve_vehicle_spec
        ),
        "tl_info": handler(
            lambda p: p.message("morai_msgs/MoraiTLInfoSrvRequest"), lights.serve_tl_info
        ),
        "scenario_load_srv": prepared_handler(
            lambda p: p.message("morai_msgs/MoraiScenarioLoadSrvRequest"),
            scenarios.prepare_scenario_service,
            scenarios.serve_scenario_load,
        ),
        "sync_mode_cmd": handler(
            lambda p: p.message("morai_msgs/MoraiSyncModeCmdSrvRequest"),
            sync_mode.serve_sync_mode_cmd,
        ),
        "sync_mode_wait_for_tick": handler(
            lambda p: p.message("morai_msgs/MoraiWaitForTickSrvRequest"),
            sync_mode.serve_wait_for_tick,
        ),
        "sync_mode_ctrl_cmd": handler(
            lambda p: p.message("morai_msgs/MoraiSyncModeCtrlCmdSrvRequest"),
            sync_mode.serve_ctrl_cmd,
        ),
        "sync_mode_set_gear": handler(
            lambda p: p.message("morai_msgs/MoraiSyncModeSetGearSrvRequest"),
            sync_mode.serve_set_gear,
        ),
        "sync_mode_scenario_load": prepared_handler(
            lambda p: p.message("morai_msgs/MoraiSyncModeSLSrvRequest"),
            scenarios.prepare_scenario_service,
            sync_mode.serve_scenario_load,
        ),
        "sync_mode_add_object": handler(
            lambda p: p.message("morai_msgs/MoraiSyncModeAddObjectSrvRequest"),
            sync_objects.serve_add_object,
        ),
        "sync_mode_remove_object": handler(
            lambda p: p.message("morai_msgs/MoraiSyncModeRemoveObjectSrvRequest"),
            sync_objects.serve_remove_object,
        ),
        "sim_proc": handler(
            lambda p: p.message("morai_msgs/MoraiSimProcSrvRequest"), replay_rows.serve_sim_proc
        ),
    },
    openers={"camera": camera_rows.open_camera_rows},
    release_adapters={
        # the request as a 2021.08 client sent it (its WaitForTick carries the CtrlCmd)
        ("sync_mode_wait_for_tick", "2021.08"): handler(
            lambda _: get_profile("2021.08").message("morai_msgs/MoraiWaitForTickSrvRequest"),
            sync_mode.apply_tick_command,
        ),
    },
    latched={"markers": markers.build_map_markers},
    unheard={
        "collision": objects.pass_collisions,
        "vehicle_collision": objects.pass_vehicle_collisions,
    },
)
