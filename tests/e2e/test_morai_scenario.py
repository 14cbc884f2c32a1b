"""A MORAI SIM scenario file loaded by a real rospy client: /ScenarioLoad with its `.json`
name, /Service_MoraiSL with the bare name MORAI SIM's own clients send, the result seen
in /Object_topic."""

from __future__ import annotations

import pytest

from tests import morai_scenarios as morai

pytestmark = pytest.mark.ros

OBJECTS = ("/Object_topic", "morai_msgs/ObjectStatusList")
SCENARIO_SRV = ("/Service_MoraiSL", "morai_msgs/MoraiScenarioLoadSrv")
TOWN_NPCS = 8
"""The default town scenario's NPCs, there before any load."""


def test_scenario_load_of_a_morai_json_places_its_npcs(egosim, rospy_client) -> None:
    simulator = egosim()
    document = morai.scenario(
        "town",
        morai.ego(morai.on_link("R5_E_1", 0.25)),
        vehicles=(
            # R5_E_1 runs east along y = -91.75 from x = -76 for 152 m: mid-link is x = 0.
            morai.npc(morai.on_link("R5_E_1", 0.5), 1, data_id=30100010, active_distance=5.0),
            morai.npc(morai.on_link("R5_E_2", 0.5), 2, data_id=30200003, active_distance=5.0),
        ),
        pedestrians=(morai.pedestrian(20.0, -84.0, -90.0, 3, active_distance=5.0),),
        objects=(morai.thing(30.0, -99.0, 0.0, 4, 40100005),),
    )
    morai.write(simulator.data_root, "traffic.json", document)
    client = rospy_client(simulator)
    client.subscribe(*OBJECTS)
    assert client.next_message(OBJECTS[0])["num_of_npcs"] == TOWN_NPCS
    flags = {
        "load_ego_vehicle_data": True,
        "load_surrounding_vehicle_data": True,
        "load_pedestrian_data": True,
        "load_obstacle_data": True,
    }
    client.publish(
        "/ScenarioLoad",
        "morai_msgs/ScenarioLoad",
        {"file_name": "traffic.json", "delete_all": True, **flags},
    )
    loaded = client.next_message(OBJECTS[0])
    while loaded["num_of_npcs"] == TOWN_NPCS:
        loaded = client.next_message(OBJECTS[0])
    assert (loaded["num_of_npcs"], loaded["num_of_pedestrian"], loaded["num_of_obstacle"]) == (
        2,
        1,
        1,
    )
    npcs = sorted(loaded["npc_list"], key=lambda o: o["position"]["y"])
    assert [o["name"] for o in npcs] == ["2016_Kia_Niro(HEV)", "2016_Hyundai_Ioniq"]
    # Dormant (the ego is 38 m away): they stand where the file puts them.
    assert npcs[1]["position"]["x"] == pytest.approx(0.0, abs=2.5)
    assert npcs[1]["position"]["y"] == pytest.approx(-91.75, abs=0.1)
    assert all(o["velocity"]["x"] == 0.0 for o in npcs)

    request = {"file_name": "traffic", "delete_all": False, "load_surrounding_vehicle_data": True}
    assert client.call(*SCENARIO_SRV, {"request": request})["response"]["result"] is True
    assert client.next_message(OBJECTS[0])["num_of_npcs"] == 4
