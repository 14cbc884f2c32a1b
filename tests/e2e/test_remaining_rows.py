"""Rows whose effect a client sees on another row: NPC-NPC collisions, /lamps,
/SensorPosControl."""

from __future__ import annotations

import math

import pytest

from egosim.world.vehicle import DEFAULT_EGO_MODEL, sensor_mount_origin, vehicle_model
from tests.waiting import until

pytestmark = pytest.mark.ros

OBJECTS = ("/Object_topic", "morai_msgs/ObjectStatusList")
NPC_GHOST = ("/NpcGhost_Topic", "morai_msgs/NpcGhostCmd")
VEHICLE_COLLISIONS = ("/VehicleCollisionData", "morai_msgs/VehicleCollisionData")
EVENT = ("/Service_MoraiEventCmd", "morai_msgs/MoraiEventCmdSrv")
TF = ("/tf", "tf2_msgs/TFMessage")


def test_npc_crash_is_one_vehicle_collision_with_both_vehicles(egosim, rospy_client) -> None:
    client = rospy_client(egosim())
    client.subscribe(*OBJECTS)
    client.subscribe(*VEHICLE_COLLISIONS)
    npc = client.next_message(OBJECTS[0])["npc_list"][0]
    position = npc["position"]
    ghost = {
        "unique_id": 9000,
        "name": "2016_Kia_Niro(HEV)",
        "position": {"x": position["x"], "y": position["y"], "z": 0.0},
        "rpy": {"x": 0.0, "y": 0.0, "z": npc["heading"]},
    }
    since = client.received(VEHICLE_COLLISIONS[0])
    client.publish(*NPC_GHOST, {"npc_list": [ghost]})
    crashes = []
    while not crashes:
        received = client.messages(VEHICLE_COLLISIONS[0], since=since, count=1, timeout=30)
        assert received, "no VehicleCollisionData"
        since += len(received)
        crashes = [c for m in received for c in m["collisions"]]
    assert len(crashes) == 1
    ids = {v["unique_id"] for v in crashes[0]["crashed_vehicles"]}
    assert ids == {npc["unique_id"], 9000}
    # The ghost stands where the NPC was: the NPC is pushed out beside it and stays in
    # contact, which every later message lists (as the same pair, no new crash).
    later = client.messages(VEHICLE_COLLISIONS[0], since=since, count=5)
    for message in later:
        pairs = [{v["unique_id"] for v in c["crashed_vehicles"]} for c in message["collisions"]]
        assert pairs == [ids]


def test_lamps_topic_sets_the_ego_lamps(egosim, rospy_client) -> None:
    client = rospy_client(egosim("--map", "straight"))
    client.publish("/lamps", "morai_msgs/Lamps", {"turnSignal": 1, "emergencySignal": 1})

    def lamps_on() -> dict | None:
        lamps = client.call(*EVENT, {"request": {"option": 0, "gear": -1}})["response"]["lamps"]
        return lamps if lamps["turnSignal"] == 1 else None

    lamps = until(lamps_on, "EventCmd to report the left turn signal")
    assert lamps["emergencySignal"] == 1


def test_sensor_pos_control_moves_the_lidar_mount(egosim, rospy_client) -> None:
    client = rospy_client(egosim("--map", "straight"))
    client.subscribe(*TF)
    command = {
        "sensor_index": [2],
        "pose_x": [1.5],
        "pose_y": [0.0],
        "pose_z": [2.2],
        "roll": [0.0],
        "pitch": [0.0],
        "yaw": [math.pi / 2],
    }
    client.publish("/SensorPosControl", "morai_msgs/SensorPosControl", command)

    # Mounts are MORAI's: from the rear axle's midpoint at wheel-centre height.
    origin_x, _, origin_z = sensor_mount_origin(vehicle_model(DEFAULT_EGO_MODEL))

    def moved_lidar() -> dict | None:
        transforms = client.next_message(TF[0])["transforms"]
        lidar = next(t for t in transforms if t["child_frame_id"] == "lidar")["transform"]
        return lidar if lidar["translation"]["x"] == pytest.approx(1.5 + origin_x) else None

    lidar = until(moved_lidar, "/tf to show the LiDAR 1.5 m ahead of the mount origin")
    assert lidar["translation"]["z"] == pytest.approx(2.2 + origin_z)
    assert (lidar["rotation"]["z"], lidar["rotation"]["w"]) == (
        pytest.approx(math.sqrt(0.5)),
        pytest.approx(math.sqrt(0.5)),
    )
