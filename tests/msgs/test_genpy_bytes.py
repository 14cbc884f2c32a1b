"""Bytes egosim produces equal what Debian's genpy produces for the same values."""

from __future__ import annotations

import json
import subprocess
from pathlib import Path
from typing import Any

import pytest
from rosbags.typesys.base import Nodetype

from egosim.msgs import MessageType, get_profile
from egosim.msgs.defaults import default_message
from tests.contract import load_contract
from tests.debian_ros import ROS_PYTHON, require_ros

PEER = Path(__file__).parent / "peers" / "genpy_serialize.py"

HEADER = {"seq": 7, "stamp": {"secs": 1_700_000_000, "nsecs": 123_456_789}, "frame_id": "map"}
VECTOR = {"x": 1.5, "y": -2.25, "z": 0.125}


def object_status(unique_id: int, type_code: int) -> dict[str, Any]:
    return {
        "unique_id": unique_id,
        "type": type_code,
        "name": f"2016_Kia_Niro(HEV)#{unique_id}",
        "heading": 91.5,
        "velocity": {"x": 36.0, "y": 0.5, "z": 0.0},
        "acceleration": VECTOR,
        "size": {"x": 4.355, "y": 1.805, "z": 1.535},
        "position": {"x": 100.0 + unique_id, "y": -20.0, "z": 0.25},
    }


CASES: dict[str, dict[str, Any]] = {
    "morai_msgs/CtrlCmd": {
        "longlCmdType": 2,
        "accel": 0.25,
        "brake": 0.0,
        "front_steer": -0.125,
        "rear_steer": 0.01,
        "velocity": 30.0,
        "acceleration": -1.5,
    },
    "morai_msgs/EgoVehicleStatus": {
        "header": HEADER,
        "unique_id": -1,
        "acceleration": VECTOR,
        "position": {"x": 312.5, "y": -45.25, "z": 0.0},
        "velocity": {"x": 13.9, "y": 0.01, "z": 0.0},
        "heading": 179.5,
        "accel": 0.5,
        "brake": 0.0,
        "front_steer_angle": 3.5,
        "rear_steer_angle": 0.0,
        "lateral_offset": 0.25,
        "tire_lateral_force_fl": 1200.0,
        "side_slip_angle_rr": -0.01,
        "tire_cornering_stiffness_fr": 40000.0,
        "distance_left_lane_boundary": 1.5,
        "distance_right_lane_boundary": 2.0,
        "cross_track_error": -0.25,
    },
    "morai_msgs/ObjectStatusList": {
        "header": HEADER,
        "num_of_npcs": 2,
        "num_of_pedestrian": 1,
        "num_of_obstacle": 0,
        "npc_list": [object_status(2, 1), object_status(3, 1)],
        "pedestrian_list": [object_status(10, 0)],
        "obstacle_list": [],
    },
    "morai_msgs/MoraiEventCmdSrvRequest": {
        "request": {
            "option": 6,
            "ctrl_mode": 3,
            "gear": 4,
            "lamps": {"header": HEADER, "turnSignal": 1, "emergencySignal": 0},
            "set_pause": False,
        }
    },
    "morai_msgs/MoraiEventCmdSrvResponse": {
        "response": {
            "option": 2,
            "ctrl_mode": 3,
            "gear": 2,
            "lamps": {"header": HEADER, "turnSignal": 0, "emergencySignal": 1},
            "set_pause": True,
        }
    },
}


def contract_definition(name: str) -> str:
    contract = load_contract("26.r1")
    if name in contract["messages"]:
        return contract["messages"][name]["definition"]
    service, half = name.removesuffix("Request"), "request"
    if name.endswith("Response"):
        service, half = name.removesuffix("Response"), "response"
    return contract["services"][service][f"{half}_definition"]


def build(message_type: MessageType, store_name: str, values: dict[str, Any]) -> Any:
    """A rosbags message from nested plain values (the same ones genpy gets)."""
    store = message_type.store
    fields = dict(store.fielddefs[store_name][1])
    built = {}
    for name, value in values.items():
        nodetype, args = fields[name]
        if name == "stamp":
            built[name] = store.types["builtin_interfaces/msg/Time"](
                sec=value["secs"], nanosec=value["nsecs"]
            )
        elif nodetype == Nodetype.NAME:
            built[name] = build(message_type, args, value)
        elif nodetype == Nodetype.SEQUENCE and args[0][0] == Nodetype.NAME:
            built[name] = [build(message_type, args[0][1], item) for item in value]
        else:
            built[name] = value
    return default_message(store, store_name, **built)


@pytest.mark.ros
@pytest.mark.parametrize("name", sorted(CASES))
def test_bytes_equal_genpy(name: str) -> None:
    require_ros()
    message_type = get_profile("26.r1").message(name)
    ours = message_type.serialize(build(message_type, message_type.store_name, CASES[name]))
    request = {"type": name, "definition": contract_definition(name), "values": CASES[name]}
    result = subprocess.run(
        [ROS_PYTHON, str(PEER)],
        input=json.dumps(request),
        capture_output=True,
        text=True,
        check=True,
        timeout=60,
    )
    assert ours.hex() == result.stdout
