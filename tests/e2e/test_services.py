"""The simulator's services, called by a real rospy client with contract-generated classes."""

from __future__ import annotations

import math
import statistics
import xmlrpc.client
from itertools import pairwise

import pytest

from egosim.world.vehicle import vehicle_model
from tests.e2e import scenarios

pytestmark = pytest.mark.ros

EGO = ("/Ego_topic", "morai_msgs/EgoVehicleStatus")
OBJECTS = ("/Object_topic", "morai_msgs/ObjectStatusList")
CTRL = ("/ctrl_cmd", "morai_msgs/CtrlCmd")
EVENT = ("/Service_MoraiEventCmd", "morai_msgs/MoraiEventCmdSrv")
SCENARIO_SRV = ("/Service_MoraiSL", "morai_msgs/MoraiScenarioLoadSrv")


def event(option: int, **fields) -> dict:
    return {"request": {"option": option, "gear": -1, **fields}}


@pytest.fixture(scope="module")
def town(module_egosim):
    """One simulator on the town for the tests that only ask its specs."""
    return module_egosim()


def test_map_spec_is_the_town_georeference(town, rospy_client) -> None:
    client = rospy_client(town)
    spec = client.call(
        "/Service_MoraiMapSpec", "morai_msgs/MoraiMapSpecSrv", {"request": {"load_map_data": True}}
    )["response"]
    assert spec["plane_coordinate_system"] == 0
    assert spec["utm_num"] == 52
    assert spec["central_meridian"] == pytest.approx(129.0)
    assert (spec["utm_offset"]["x"], spec["utm_offset"]["y"]) == (313000.0, 4161000.0)
    assert spec["ellipse"] == "WGS84"


def test_vehicle_spec_for_ego_npc_and_unknown(town, rospy_client) -> None:
    client = rospy_client(town)
    client.subscribe(*EGO)
    client.subscribe(*OBJECTS)
    ego_id = client.next_message(EGO[0])["unique_id"]
    npc = client.next_message(OBJECTS[0])["npc_list"][0]

    def spec(unique_id: int) -> dict:
        return client.call(
            "/Service_MoraiVehicleSpec",
            "morai_msgs/MoraiVehicleSpecSrv",
            {"request": {"unique_id": unique_id}},
        )["response"]

    niro = vehicle_model("2016_Kia_Niro(HEV)")
    ego = spec(ego_id)
    assert ego["wheel_base"] == pytest.approx(niro.wheelbase, abs=1e-5)
    assert ego["max_steering"] == pytest.approx(math.degrees(niro.max_steer_front))
    assert ego["size"]["x"] == pytest.approx(niro.length)
    other = spec(npc["unique_id"])
    # VehicleSpec's size runs along the vehicle's axes (length first); ObjectStatus lists
    # width, length, height.
    assert (other["size"]["x"], other["size"]["y"]) == pytest.approx(
        (npc["size"]["y"], npc["size"]["x"])
    )
    assert other["wheel_base"] == pytest.approx(vehicle_model(npc["name"]).wheelbase, abs=1e-5)
    assert spec(999_999) == {
        "size": {"x": 0.0, "y": 0.0, "z": 0.0},
        "wheel_base": 0.0,
        "max_steering": 0.0,
        "overhang": 0.0,
        "rear_overhang": 0.0,
    }


def test_event_gear_reverse_then_throttle_backs_up(egosim, rospy_client) -> None:
    client = rospy_client(egosim("--map", "straight"))
    client.subscribe(*EGO)
    reply = client.call(*EVENT, event(2, gear=2))["response"]
    assert reply["gear"] == 2
    assert reply["ctrl_mode"] == 3
    client.stream(*CTRL, {"longlCmdType": 1, "accel": 0.4}, rate=50)
    moving = [client.next_message(EGO[0]) for _ in range(50)][-1]
    client.stop_stream(CTRL[0])
    assert moving["velocity"]["x"] < -0.3
    unchanged = client.call(*EVENT, event(2))["response"]
    assert unchanged["gear"] == 2


def test_event_lamps_and_pause(egosim, rospy_client) -> None:
    client = rospy_client(egosim("--map", "straight"))
    client.subscribe(*EGO)
    lamps = {"turnSignal": 2, "emergencySignal": 1}
    reply = client.call(*EVENT, event(4 | 8, lamps=lamps, set_pause=True))["response"]
    assert (reply["lamps"]["turnSignal"], reply["lamps"]["emergencySignal"]) == (2, 1)
    assert reply["set_pause"] is True
    client.stream(*CTRL, {"longlCmdType": 1, "accel": 1.0}, rate=50)
    frozen = [client.next_message(EGO[0]) for _ in range(20)]
    assert {m["position"]["x"] for m in frozen} == {frozen[0]["position"]["x"]}
    assert client.call(*EVENT, event(8, set_pause=False))["response"]["set_pause"] is False
    moving = [client.next_message(EGO[0]) for _ in range(50)][-1]
    client.stop_stream(CTRL[0])
    assert moving["position"]["x"] > frozen[0]["position"]["x"]


def test_event_ctrl_mode_keyboard_ignores_ctrl_cmd(egosim, rospy_client) -> None:
    client = rospy_client(egosim("--map", "straight"))
    client.subscribe(*EGO)
    assert client.call(*EVENT, event(1, ctrl_mode=1))["response"]["ctrl_mode"] == 1
    client.stream(*CTRL, {"longlCmdType": 1, "accel": 1.0}, rate=50)
    still = [client.next_message(EGO[0]) for _ in range(30)][-1]
    client.stop_stream(CTRL[0])
    assert still["velocity"]["x"] == pytest.approx(0.0, abs=1e-6)


def test_scenario_load_service_replaces_the_objects(egosim, rospy_client) -> None:
    simulator = egosim()
    scenarios.write(simulator.data_root, "two_npcs.yaml", scenarios.TWO_NPCS)
    client = rospy_client(simulator)
    client.subscribe(*OBJECTS)
    assert client.next_message(OBJECTS[0])["num_of_npcs"] == 8
    request = {
        "file_name": "two_npcs",
        "delete_all": True,
        "load_ego_vehicle_data": True,
        "load_surrounding_vehicle_data": True,
        "load_pedestrian_data": True,
        "load_obstacle_data": True,
    }
    assert client.call(*SCENARIO_SRV, {"request": request})["response"]["result"] is True
    loaded = client.next_message(OBJECTS[0])
    assert (loaded["num_of_npcs"], loaded["num_of_pedestrian"], loaded["num_of_obstacle"]) == (
        2,
        0,
        0,
    )


@pytest.mark.parametrize("file_name", ["missing", "../outside", "/etc/passwd"])
def test_scenario_load_service_refuses_bad_names(egosim, rospy_client, file_name: str) -> None:
    simulator = egosim()
    client = rospy_client(simulator)
    client.subscribe(*OBJECTS)
    reply = client.call(*SCENARIO_SRV, {"request": {"file_name": file_name, "delete_all": True}})
    assert reply["response"]["result"] is False
    assert client.next_message(OBJECTS[0])["num_of_npcs"] == 8


def test_scenario_load_topic_with_pause(egosim, rospy_client) -> None:
    simulator = egosim()
    scenarios.write(simulator.data_root, "two_npcs.yaml", scenarios.TWO_NPCS)
    client = rospy_client(simulator)
    client.subscribe(*OBJECTS)
    client.subscribe(*EGO)
    client.publish(
        "/ScenarioLoad",
        "morai_msgs/ScenarioLoad",
        {
            "file_name": "two_npcs.yaml",
            "delete_all": True,
            "load_surrounding_vehicle_data": True,
            "set_pause": True,
        },
    )
    while client.next_message(OBJECTS[0])["num_of_npcs"] != 2:
        pass
    paused = [client.next_message(OBJECTS[0]) for _ in range(5)]
    positions = {tuple(sorted(o["position"]["x"] for o in m["npc_list"])) for m in paused}
    assert len(positions) == 1


LIVE_SETTINGS = """\
map: straight
network:
  rows:
    ego_status: {rate_hz: 10}
    object_status: {name: /objects}
    collision: {enabled: false}
"""


def test_scenario_network_settings_apply_live_and_keep_unchanged_connections(
    egosim, rospy_client
) -> None:
    simulator = egosim("--map", "straight")
    scenarios.write(simulator.data_root, "live.yaml", LIVE_SETTINGS)
    client = rospy_client(simulator)
    client.subscribe(*EGO)
    client.wait_connected(EGO[0])
    request = {"file_name": "live.yaml", "load_network_connection_data": True}
    assert client.call(*SCENARIO_SRV, {"request": request})["response"]["result"] is True

    # The same /Ego_topic connection goes on, now at 10 Hz. Header stamps are wall times in
    # real time: a loop late on a busy machine runs its ticks back to back, so one gap may
    # be long and the next short; the median is the row's period.
    seen = client.received(EGO[0])
    stamps = [m["header"]["stamp"] for m in client.messages(EGO[0], since=seen + 2, count=8)]
    gaps = [b - a for a, b in pairwise(stamps)]
    assert statistics.median(gaps) == pytest.approx(0.1, abs=0.02), gaps
    # /Object_topic moved to /objects; /CollisionData is gone.
    client.subscribe("/objects", OBJECTS[1])
    assert client.next_message("/objects")["num_of_npcs"] == 0
    _, _, (published, _, _) = xmlrpc.client.ServerProxy(simulator.master_uri).getSystemState("/t")
    topics = {topic for topic, _ in published}
    assert "/objects" in topics
    assert "/Object_topic" not in topics and "/CollisionData" not in topics
