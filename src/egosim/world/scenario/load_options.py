"""ScenarioLoad's flags, and what a load did."""

from __future__ import annotations

from dataclasses import dataclass

from egosim.json_value import JsonObject


@dataclass(frozen=True)
class ScenarioLoadOptions:
    """The flags of morai_msgs/ScenarioLoad (file_name is the bridge's business).

    delete_all: remove every NPC, pedestrian and obstacle (never the ego) before loading;
        otherwise loaded objects join those already there.
    load_network_connection_data: report the file's network settings to the caller.
    load_ego_vehicle_data: put the ego(s) where the file says, with the file's model.
    load_surrounding_vehicle_data / load_pedestrian_data / load_object_data: place the
        file's NPC vehicles / pedestrians / obstacles.
    set_pause: leave the world paused after loading.
    scenario_drives_ego: an OpenSCENARIO storyboard drives the ego from its Init on (the
        ego's control mode is auto); otherwise its stack does.
    """

    delete_all: bool = True
    load_network_connection_data: bool = False
    load_ego_vehicle_data: bool = True
    load_surrounding_vehicle_data: bool = True
    load_pedestrian_data: bool = True
    load_object_data: bool = True
    set_pause: bool = False
    scenario_drives_ego: bool = False


@dataclass(frozen=True)
class ScenarioLoadReport:
    """What load_scenario did: objects placed, and the network settings requested."""

    ego_placed: bool
    npcs_spawned: int
    pedestrians_spawned: int
    obstacles_spawned: int
    network_settings: JsonObject | None
    """The file's `network` section when load_network_connection_data was set (else None)."""
    paused: bool
    notes: tuple[str, ...] = ()
    """What the load did that the caller should report (positions moved between frames)."""
