"""Ghost mode: GhostMessage places the ego, NpcGhostCmd places NPC vehicles."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

pytestmark = pytest.mark.ros

EGO = ("/Ego_topic", "morai_msgs/EgoVehicleStatus")
GHOST = ("/ghost_ctrl_cmd", "morai_msgs/GhostMessage")
NPC_GHOST = ("/NpcGhost_Topic", "morai_msgs/NpcGhostCmd")
OBJECTS = ("/Object_topic", "morai_msgs/ObjectStatusList")
COLLISION = ("/CollisionData", "morai_msgs/CollisionData")
MODEL = "2016_Kia_Niro(HEV)"


def ghost_input(tmp_path: Path) -> str:
    path = tmp_path / "ghost_network.yaml"
    path.write_text("ego_input: GhostCtrlCmd\n", encoding="utf-8")
    return str(path)


def npc_ghost(unique_id: int, x: float, y: float, **fields) -> dict:
    info = {
        "unique_id": unique_id,
        "name": MODEL,
        "position": {"x": x, "y": y, "z": 0.0},
        "rpy": {"x": 0.0, "y": 0.0, "z": fields.pop("yaw_deg", 0.0)},
    }
    return {**info, **fields}


def listed(objects: dict, unique_id: int) -> dict | None:
    return next((o for o in objects["npc_list"] if o["unique_id"] == unique_id), None)


def wait_for_object(client, unique_id: int, present: bool = True, tries: int = 100) -> dict:
    for _ in range(tries):
        message = client.next_message(OBJECTS[0])
        if (listed(message, unique_id) is not None) == present:
            return message
    raise AssertionError(f"object {unique_id} {'never appeared' if present else 'stayed'}")


def test_ghost_message_places_the_ego_at_the_commanded_pose(egosim, rospy_client, tmp_path):
    client = rospy_client(egosim("--map", "straight", "--network", ghost_input(tmp_path)))
    client.subscribe(*EGO)
    command = {
        "position": {"x": 120.0, "y": -1.75, "z": 0.0},
        "rotation": {"x": 0.0, "y": 0.0, "z": 30.0},
        "velocity": 36.0,
        "steering_angle": 2.0,
    }
    client.stream(*GHOST, command, rate=100)
    status = [client.next_message(EGO[0]) for _ in range(20)][-1]
    client.stop_stream(GHOST[0])
    # Between two messages (10 ms apart) the ego moves on at the commanded 10 m/s.
    heading = math.radians(30.0)
    offset = (status["position"]["x"] - 120.0, status["position"]["y"] + 1.75)
    along = offset[0] * math.cos(heading) + offset[1] * math.sin(heading)
    assert -0.01 <= along < 0.5
    assert math.hypot(*offset) == pytest.approx(along, abs=0.02)
    assert status["heading"] == pytest.approx(30.0, abs=0.5)
    assert status["velocity"]["x"] == pytest.approx(10.0, abs=0.1)
    assert status["front_steer_angle"] == pytest.approx(2.0, abs=0.05)


def test_npc_ghost_spawns_and_moves_an_npc_with_the_named_model(egosim, rospy_client):
    client = rospy_client(egosim("--map", "straight"))
    client.subscribe(*OBJECTS)
    ghost = npc_ghost(500, 60.0, -5.25, vehicle_speed=20.0, turn_signal=1, yaw_deg=10.0)
    client.publish(*NPC_GHOST, {"npc_list": [ghost]})
    npc = listed(wait_for_object(client, 500), 500)
    assert npc["name"] == MODEL
    assert npc["type"] == 1
    assert (npc["position"]["x"], npc["position"]["y"]) == pytest.approx((60.0, -5.25))
    assert npc["heading"] == pytest.approx(10.0)
    assert npc["velocity"]["x"] == pytest.approx(20.0, rel=1e-5)

    client.publish(*NPC_GHOST, {"npc_list": [npc_ghost(500, 80.0, -5.25)]})
    for _ in range(100):
        npc = listed(client.next_message(OBJECTS[0]), 500)
        if npc["position"]["x"] == pytest.approx(80.0):
            break
    assert npc["position"]["x"] == pytest.approx(80.0)
    assert npc["velocity"]["x"] == pytest.approx(0.0)


def test_npc_ghost_of_an_unknown_model_is_refused_and_the_rest_applies(egosim, rospy_client):
    simulator = egosim("--map", "straight")
    client = rospy_client(simulator)
    client.subscribe(*OBJECTS)
    bad = {**npc_ghost(600, 50.0, -5.25), "name": "No_Such_Car"}
    client.publish(*NPC_GHOST, {"npc_list": [bad, npc_ghost(601, 70.0, -5.25)]})
    message = wait_for_object(client, 601)
    assert listed(message, 600) is None
    assert message["num_of_npcs"] == 1
    assert simulator.process.popen.poll() is None


def test_an_npc_taken_over_by_a_ghost_stops_being_simulated(egosim, rospy_client):
    client = rospy_client(egosim())  # the town with its default traffic
    client.subscribe(*OBJECTS)
    before = client.next_message(OBJECTS[0])
    moving = next(o for o in before["npc_list"] if o["velocity"]["x"] > 1.0)
    count = before["num_of_npcs"]
    held = npc_ghost(
        moving["unique_id"], moving["position"]["x"], moving["position"]["y"],
        yaw_deg=moving["heading"],
    )  # fmt: skip
    client.publish(*NPC_GHOST, {"npc_list": [held]})
    for _ in range(100):
        npc = listed(client.next_message(OBJECTS[0]), moving["unique_id"])
        if npc is not None and npc["velocity"]["x"] == 0.0:
            break
    later = [client.next_message(OBJECTS[0]) for _ in range(10)][-1]
    npc = listed(later, moving["unique_id"])
    assert npc is not None, "the ghost left the object list"
    assert npc["name"] == moving["name"]
    assert (npc["position"]["x"], npc["position"]["y"]) == pytest.approx(
        (moving["position"]["x"], moving["position"]["y"])
    )
    assert later["num_of_npcs"] == count


def test_the_ego_collides_with_an_npc_ghost_driven_into_it(egosim, rospy_client):
    client = rospy_client(egosim("--map", "straight"))
    client.subscribe(*EGO)
    client.subscribe(*COLLISION)
    ego = client.next_message(EGO[0])
    x, y = ego["position"]["x"], ego["position"]["y"]
    client.publish(*NPC_GHOST, {"npc_list": [npc_ghost(700, x + 20.0, y)]})
    client.publish(*NPC_GHOST, {"npc_list": [npc_ghost(700, x + 2.0, y)]})
    for _ in range(200):
        report = client.next_message(COLLISION[0])
        if report["collision_object"]:
            break
    assert [o["unique_id"] for o in report["collision_object"]] == [700]
