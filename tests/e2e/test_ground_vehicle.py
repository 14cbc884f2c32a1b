"""A rospy client drives a skid-steer ego through each ground vehicle input the network
settings select (WeBOT Twist, GVDirectCmd, GVStateCmd) and sees it on /Ego_topic."""

from __future__ import annotations

import math
import time
from pathlib import Path
from typing import Any

import pytest

pytestmark = pytest.mark.ros

EGO = ("/Ego_topic", "morai_msgs/EgoVehicleStatus")
WARNING_TIMEOUT_S = 30.0


def simulator_with(egosim, tmp_path: Path, model: str, ego_input: str | None):
    scenario = tmp_path / f"{model}.yaml"
    scenario.write_text(
        f"map: straight\nego:\n  model: {model}\n  start: {{lane: R1_E_1, s: 20.0}}\n"
    )
    args = ["--map", "straight", "--scenario", str(scenario)]
    if ego_input is not None:
        network = tmp_path / "network.yaml"
        network.write_text(f"ego_input: {ego_input}\n")
        args += ["--network", str(network)]
    return egosim(*args)


def stamp(message: dict[str, Any]) -> float:
    value = message["header"]["stamp"]
    return value if isinstance(value, float | int) else value["secs"] + value["nsecs"] * 1e-9


def ego_messages_for(client, seconds: float) -> list[dict[str, Any]]:
    """Every /Ego_topic message over the next `seconds` of header time."""
    since = client.received(EGO[0])
    received: list[dict[str, Any]] = []
    while not received or stamp(received[-1]) < stamp(received[0]) + seconds:
        batch = client.messages(EGO[0], since=since, count=1)
        since += len(batch)
        received += batch
    return received


def yaw_rate_deg(first: dict[str, Any], last: dict[str, Any]) -> float:
    """Mean heading rate between two messages, deg/s (unwrapped across ±180)."""
    change = math.remainder(last["heading"] - first["heading"], 360.0)
    return change / (stamp(last) - stamp(first))


def drive_and_watch(client, topic: str, type_name: str, command: dict[str, Any]):
    """Stream `command`, let the ego settle, and return its steady /Ego_topic messages."""
    client.subscribe(*EGO)
    start = client.next_message(EGO[0])
    client.stream(topic, type_name, command, rate=50)
    ego_messages_for(client, 3.0)
    steady = ego_messages_for(client, 1.0)
    client.stop_stream(topic)
    return start, steady


def wait_for_warning(simulator, text: str) -> str:
    deadline = time.monotonic() + WARNING_TIMEOUT_S
    while text not in (log := simulator.process.stderr_text()):
        if time.monotonic() > deadline:
            pytest.fail(f"no log line with {text!r}; stderr: {log[-3000:]}")
        time.sleep(0.1)
    return log


def test_webot_twist_drives_forward_and_turns_left(egosim, rospy_client, tmp_path) -> None:
    client = rospy_client(
        simulator_with(egosim, tmp_path, "WeBOT_Indoor_Robot", "WeBOTCmdController")
    )
    twist = {"linear": {"x": 1.0}, "angular": {"z": 0.5}}
    start, steady = drive_and_watch(client, "/commands/vel", "geometry_msgs/Twist", twist)
    assert start["velocity"]["x"] == pytest.approx(0.0, abs=1e-6)
    assert steady[-1]["velocity"]["x"] == pytest.approx(1.0, abs=0.01)
    assert yaw_rate_deg(steady[0], steady[-1]) == pytest.approx(math.degrees(0.5), rel=0.05)


def test_gv_direct_cmd_throttle_and_right_skid(egosim, rospy_client, tmp_path) -> None:
    client = rospy_client(simulator_with(egosim, tmp_path, "UGV_6W_Skid_Steer", "GVDirectCmd"))
    command = {"steerType": 0, "throttle": 0.4, "skidSteering": -0.1}
    start, steady = drive_and_watch(client, "/gv_direct_cmd", "morai_msgs/GVDirectCmd", command)
    # Sides at (0.4 ± 0.1) of 5 m/s: forward 2 m/s, turning clockwise.
    assert steady[-1]["velocity"]["x"] == pytest.approx(2.0, abs=0.02)
    assert steady[-1]["accel"] == pytest.approx(0.4, abs=1e-6)
    assert yaw_rate_deg(steady[0], steady[-1]) < -5.0
    assert steady[-1]["position"]["x"] > start["position"]["x"] + 2.0


def test_gv_state_cmd_reaches_its_speed_and_turn_rate(egosim, rospy_client, tmp_path) -> None:
    client = rospy_client(simulator_with(egosim, tmp_path, "WeBOT_Indoor_Robot", "GVStateCmd"))
    command = {"latCtrlType": 0, "targetLongitudinalVelocity": 0.6, "targetAngularVelocity": -0.4}
    _, steady = drive_and_watch(client, "/gv_state_cmd", "morai_msgs/GVStateCmd", command)
    assert steady[-1]["velocity"]["x"] == pytest.approx(0.6, abs=0.01)
    assert yaw_rate_deg(steady[0], steady[-1]) == pytest.approx(math.degrees(-0.4), rel=0.05)


def test_ctrl_cmd_leaves_a_skid_steer_ego_standing(egosim, rospy_client, tmp_path) -> None:
    simulator = simulator_with(egosim, tmp_path, "WeBOT_Indoor_Robot", None)
    client = rospy_client(simulator)
    command = {"longlCmdType": 1, "accel": 1.0}
    _, steady = drive_and_watch(client, "/ctrl_cmd", "morai_msgs/CtrlCmd", command)
    assert steady[-1]["velocity"]["x"] == 0.0
    log = wait_for_warning(simulator, "ctrl_cmd ignored")
    assert log.count("ctrl_cmd ignored") == 1


def test_gv_direct_cmd_leaves_a_car_standing(egosim, rospy_client, tmp_path) -> None:
    simulator = simulator_with(egosim, tmp_path, "2016_Kia_Niro(HEV)", "GVDirectCmd")
    client = rospy_client(simulator)
    command = {"steerType": 0, "throttle": 1.0}
    _, steady = drive_and_watch(client, "/gv_direct_cmd", "morai_msgs/GVDirectCmd", command)
    assert steady[-1]["velocity"]["x"] == 0.0
    log = wait_for_warning(simulator, "gv_direct_cmd ignored")
    assert log.count("gv_direct_cmd ignored") == 1
