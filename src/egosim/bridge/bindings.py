"""Which handler serves each row of the protocol table."""

from __future__ import annotations

from . import ego, events, ground_vehicle, lights, objects, scenarios, specs
from .core import Handlers

HANDLERS = Handlers(
    publishers={
        "ego_status": ego.publish_ego_status,
        "object_status": objects.publish_object_list,
        "collision": objects.publish_collision,
        "vehicle_collision": objects.publish_vehicle_collisions,
        "traffic_light_status": lights.publish_traffic_light_status,
        "intersection_status": lights.publish_intersection_status,
    },
    subscribers={
        "ctrl_cmd": ego.on_ctrl_cmd,
        "webot_cmd": ground_vehicle.on_webot_cmd,
        "gv_direct_cmd": ground_vehicle.on_gv_direct_cmd,
        "gv_state_cmd": ground_vehicle.on_gv_state_cmd,
        "set_traffic_light": lights.on_set_traffic_light,
        "intersection_control": lights.on_intersection_control,
        "scenario_load": scenarios.on_scenario_load,
        "lamps": events.on_lamps,
    },
    services={
        "event_cmd": events.serve_event_cmd,
        "map_spec": specs.serve_map_spec,
        "vehicle_spec": specs.serve_vehicle_spec,
        "tl_info": lights.serve_tl_info,
        "scenario_load_srv": scenarios.serve_scenario_load,
    },
)
