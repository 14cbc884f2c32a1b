"""A MORAI client drives the ego: /ctrl_cmd in, /Ego_topic out."""

from __future__ import annotations

import pytest

pytestmark = pytest.mark.ros

EGO = ("/Ego_topic", "morai_msgs/EgoVehicleStatus")
CTRL = ("/ctrl_cmd", "morai_msgs/CtrlCmd")


def test_throttle_raises_speed(egosim, rospy_client) -> None:
    client = rospy_client(egosim("--map", "straight"))
    client.subscribe(*EGO)
    start = client.next_message(EGO[0])
    assert start["velocity"]["x"] == pytest.approx(0.0, abs=0.01)
    client.stream(*CTRL, {"longlCmdType": 1, "accel": 0.6, "brake": 0.0}, rate=50)
    moving = [client.next_message(EGO[0]) for _ in range(60)][-1]
    client.stop_stream(CTRL[0])
    assert moving["velocity"]["x"] > 1.0
    assert moving["accel"] == pytest.approx(0.6, abs=1e-6)
    assert moving["position"]["x"] > start["position"]["x"]


def test_velocity_mode_reaches_its_target(egosim, rospy_client) -> None:
    client = rospy_client(egosim("--map", "straight", "--clock", "sim", "--rtf", "4"))
    client.subscribe(*EGO)
    client.stream(*CTRL, {"longlCmdType": 2, "velocity": 30.0}, rate=50)
    speeds = []
    since = client.received(EGO[0])
    while not speeds or speeds[-1][0] < speeds[0][0] + 15.0:
        received = client.messages(EGO[0], since=since, count=1)
        since += len(received)
        speeds += [(m["header"]["stamp"], m["velocity"]["x"] * 3.6) for m in received]
    client.stop_stream(CTRL[0])
    assert speeds[-1][1] == pytest.approx(30.0, abs=0.5)
    assert max(kmh for _, kmh in speeds) < 32.0
