"""`egosim run --scenario FILE` alone runs the scenario's own map, seen by a rospy client."""

from __future__ import annotations

from pathlib import Path

import pytest

pytestmark = pytest.mark.ros

GALLERY = Path(__file__).parents[2] / "examples" / "scenarios"
EGO = ("/Ego_topic", "morai_msgs/EgoVehicleStatus")
LIGHT = ("/GetTrafficLightStatus", "morai_msgs/GetTrafficLightStatus")


def test_a_gallery_scenario_runs_on_the_mgeo_sample_without_map(egosim, rospy_client) -> None:
    client = rospy_client(egosim("--scenario", str(GALLERY / "red_light.yaml")))
    client.subscribe(*EGO)
    client.subscribe(*LIGHT)
    ego = client.next_message(EGO[0])
    # R3_E_1 of the MGeo sample runs from 120 m west of the junction towards it, 1.75 m
    # south of the axis (the ego starts at its start at 40 km/h).
    assert -120.5 < ego["position"]["x"] < -20.0
    assert ego["position"]["y"] == pytest.approx(-1.75, abs=0.1)
    light = client.next_message(LIGHT[0])
    assert light["trafficLightIndex"] == "TL1_W"
