"""The world as a MORAI client sees it: objects, collisions, lights, intersections."""

from __future__ import annotations

import itertools
import math

import pytest

from egosim.world.map import build_builtin_map
from egosim.world.traffic.catalogue import OBSTACLE_MODELS, PEDESTRIAN_MODELS
from egosim.world.vehicle.catalogue import VEHICLE_CATALOGUE
from tests.e2e import scenarios
from tests.waiting import until

pytestmark = pytest.mark.ros

EGO = ("/Ego_topic", "morai_msgs/EgoVehicleStatus")
OBJECTS = ("/Object_topic", "morai_msgs/ObjectStatusList")
CTRL = ("/ctrl_cmd", "morai_msgs/CtrlCmd")


def distance(a: dict, b: dict) -> float:
    return math.hypot(a["x"] - b["x"], a["y"] - b["y"])


def test_object_list_counts_everything_and_orders_closest_first(egosim, rospy_client) -> None:
    client = rospy_client(egosim())
    client.subscribe(*OBJECTS)
    client.subscribe(*EGO)
    objects = client.next_message(OBJECTS[0])
    ego = client.next_message(EGO[0])
    assert (objects["num_of_npcs"], objects["num_of_pedestrian"], objects["num_of_obstacle"]) == (
        8,
        6,
        4,
    )
    listed = objects["npc_list"] + objects["pedestrian_list"] + objects["obstacle_list"]
    assert len(listed) <= 20
    # Ordered by distance from the ego's footprint centre, which sits up to a metre from
    # the reference point /Ego_topic reports.
    for kind in ("npc_list", "pedestrian_list", "obstacle_list"):
        ranges = [distance(o["position"], ego["position"]) for o in objects[kind]]
        assert all(later >= earlier - 1.0 for earlier, later in itertools.pairwise(ranges))
    assert {o["type"] for o in objects["npc_list"]} == {1}
    assert {o["type"] for o in objects["pedestrian_list"]} == {0}
    assert {o["type"] for o in objects["obstacle_list"]} == {2}
    assert len({o["unique_id"] for o in listed}) == len(listed)
    # The document lists ObjectStatus.size as (width, length, height).
    models = {**VEHICLE_CATALOGUE, **PEDESTRIAN_MODELS, **OBSTACLE_MODELS}
    for listed_object in listed:
        model = models[listed_object["name"]]
        size = listed_object["size"]
        assert (size["x"], size["y"], size["z"]) == pytest.approx(
            (model.width, model.length, model.height)
        )


def test_object_lists_are_ordered_by_distance_from_the_position_ego_topic_reports(
    egosim, rospy_client, tmp_path
) -> None:
    data_root = tmp_path / "data"
    data_root.mkdir(exist_ok=True)
    scenario = scenarios.write(data_root, "fore_and_aft.yaml", scenarios.OBJECTS_FORE_AND_AFT)
    client = rospy_client(egosim("--scenario", str(scenario)))
    client.subscribe(*OBJECTS)
    client.subscribe(*EGO)
    ego = client.next_message(EGO[0])
    objects = client.next_message(OBJECTS[0])
    # The scene alternates objects a little behind and a little ahead of the rear axle,
    # so only this origin orders them as listed (tests/e2e/scenarios.py).
    for kind, count in (("npc_list", 2), ("obstacle_list", 4)):
        listed = objects[kind]
        ranges = [distance(o["position"], ego["position"]) for o in listed]
        assert len(listed) == count
        assert ranges == sorted(ranges)


def test_driving_into_an_obstacle_reports_one_collision(egosim, rospy_client) -> None:
    simulator = egosim("--map", "straight")
    scenario = scenarios.write(simulator.data_root, "obstacle.yaml", scenarios.OBSTACLE_AHEAD)
    simulator = egosim("--map", "straight", "--scenario", str(scenario))
    client = rospy_client(simulator)
    client.subscribe("/CollisionData", "morai_msgs/CollisionData")
    client.subscribe(*EGO)
    client.stream(*CTRL, {"longlCmdType": 1, "accel": 0.5}, rate=50)
    since = 0
    hits = []
    while not hits:
        received = client.messages("/CollisionData", since=since, count=1, timeout=30)
        assert received, "no CollisionData"
        since += len(received)
        hits = [m for m in received if m["collision_object"]]
    client.stop_stream(CTRL[0])
    hit = hits[0]
    assert len(hit["collision_object"]) == 1
    barrier = hit["collision_object"][0]
    assert barrier["type"] == 2
    assert (hit["global_offset_x"], hit["global_offset_y"]) == pytest.approx((40.0, -1.75))
    # The ego bounced off; the last throttle command holds, so it comes back and comes to
    # rest pressing against the barrier: every later message lists the lasting contact.
    settled = client.now() + 3.0
    while client.now() < settled or client.next_message(EGO[0])["velocity"]["x"] > 0.05:
        assert client.now() < settled + 20.0, "the ego never came to rest at the barrier"
    later = [client.next_message("/CollisionData") for _ in range(5)]
    assert all(
        [o["unique_id"] for o in m["collision_object"]] == [barrier["unique_id"]] for m in later
    )
    # The offsets keep recording the most recent collision.
    for message in later:
        offset = (message["global_offset_x"], message["global_offset_y"])
        assert offset == pytest.approx((40.0, -1.75))
    assert client.next_message(EGO[0])["velocity"]["x"] < 1.0


def test_red_override_stops_an_npc_before_its_stop_line(egosim, rospy_client) -> None:
    lane = build_builtin_map("town").lane("R2_E_1")
    (light,) = lane.traffic_light_ids
    stop_line_x = lane.centerline[0][0] + lane.stop_line_s
    probe = egosim("--map", "straight")
    scenario = scenarios.write(probe.data_root, "red.yaml", scenarios.RED_LIGHT_TOWN)
    client = rospy_client(egosim("--scenario", str(scenario), "--clock", "sim", "--rtf", "5"))
    client.subscribe(*OBJECTS)
    client.publish(
        "/SetTrafficLight",
        "morai_msgs/SetTrafficLight",
        {"trafficLightIndex": light, "trafficLightStatus": 1},
    )
    npc = client.next_message(OBJECTS[0])["npc_list"][0]
    deadline_stamp = None

    def stopped_npc() -> dict | None:
        nonlocal deadline_stamp
        message = client.next_message(OBJECTS[0])
        npc = message["npc_list"][0]
        stamp = message["header"]["stamp"]
        deadline_stamp = deadline_stamp or stamp + 40.0
        assert stamp < deadline_stamp, f"NPC still moving at {npc}"
        if npc["velocity"]["x"] < 0.05 and npc["position"]["x"] > stop_line_x - 30:
            return npc
        return None

    npc = until(stopped_npc, "the NPC to stop at the red light", timeout_s=60.0)
    front = npc["position"]["x"] + npc["size"]["x"] / 2
    assert front <= stop_line_x + 0.01
    status = client.call("/Morai_TLSrv", "morai_msgs/MoraiTLInfoSrv", {"request": {"idx": light}})
    assert status["response"]["status"] == 1


def test_intersection_control_sets_phase_and_time(egosim, rospy_client) -> None:
    client = rospy_client(egosim())
    client.subscribe("/InsnStatus", "morai_msgs/IntersectionStatus")
    before = client.messages("/InsnStatus", count=64)
    assert {m["intersection_index"] for m in before} == set(range(1, 33))
    client.publish(
        "/InsnControl",
        "morai_msgs/IntersectionControl",
        {"intersection_index": 6, "intersection_status": 1, "intersection_status_time": 2.0},
    )
    since = client.received("/InsnStatus")

    def controlled_status() -> dict | None:
        nonlocal since
        batch = client.messages("/InsnStatus", since=since, count=32)
        since += len(batch)
        controlled = [m for m in batch if m["intersection_index"] == 6]
        if controlled and controlled[-1]["intersection_status"] == 1:
            return controlled[-1]
        return None

    status = until(controlled_status, "intersection 6 to report phase 1")
    assert 2.0 <= status["intersection_status_time"] < 3.0


def test_traffic_light_status_follows_an_override(egosim, rospy_client) -> None:
    client = rospy_client(egosim())
    client.subscribe("/GetTrafficLightStatus", "morai_msgs/GetTrafficLightStatus")
    light = client.next_message("/GetTrafficLightStatus")
    assert light["trafficLightType"] in (0, 1, 2, 100)
    client.publish(
        "/SetTrafficLight",
        "morai_msgs/SetTrafficLight",
        {"trafficLightIndex": light["trafficLightIndex"], "trafficLightStatus": 4},
    )
    while client.next_message("/GetTrafficLightStatus")["trafficLightStatus"] != 4:
        pass
    info = client.call(
        "/Morai_TLSrv",
        "morai_msgs/MoraiTLInfoSrv",
        {"request": {"idx": light["trafficLightIndex"]}},
    )
    assert info["response"]["status"] == 4
    unknown = client.call("/Morai_TLSrv", "morai_msgs/MoraiTLInfoSrv", {"request": {"idx": "X"}})
    assert unknown["response"]["status"] == -1
