"""EventInfo.ctrl_mode: external obeys /ctrl_cmd, keyboard and gamepad get no command,
auto is driven by the simulator's own lane-following controller."""

from __future__ import annotations

import pytest

pytestmark = pytest.mark.ros

EGO = ("/Ego_topic", "morai_msgs/EgoVehicleStatus")
CTRL = ("/ctrl_cmd", "morai_msgs/CtrlCmd")
EVENT = ("/Service_MoraiEventCmd", "morai_msgs/MoraiEventCmdSrv")
SET_LIGHT = ("/SetTrafficLight", "morai_msgs/SetTrafficLight")
THROTTLE = {"longlCmdType": 1, "accel": 0.6, "brake": 0.0}
OPTION_CTRL_MODE = 1
KEYBOARD, GAMEPAD, EXTERNAL, AUTO = 1, 2, 3, 4


def set_ctrl_mode(client, mode: int) -> dict:
    request = {"request": {"option": OPTION_CTRL_MODE, "ctrl_mode": mode, "gear": -1}}
    return client.call(*EVENT, request)["response"]


def statuses(client, count: int) -> list[dict]:
    return [client.next_message(EGO[0]) for _ in range(count)]


@pytest.mark.parametrize("mode", [KEYBOARD, GAMEPAD])
def test_without_human_input_the_ego_ignores_ctrl_cmd_until_external(egosim, rospy_client, mode):
    client = rospy_client(egosim("--map", "straight"))
    client.subscribe(*EGO)
    assert set_ctrl_mode(client, mode)["ctrl_mode"] == mode
    client.stream(*CTRL, THROTTLE, rate=50)
    held = statuses(client, 30)[-1]
    assert held["velocity"]["x"] == pytest.approx(0.0, abs=0.01)
    assert held["brake"] == pytest.approx(1.0)

    assert set_ctrl_mode(client, EXTERNAL)["ctrl_mode"] == EXTERNAL
    moving = statuses(client, 60)[-1]
    client.stop_stream(CTRL[0])
    assert moving["velocity"]["x"] > 1.0


def test_auto_drives_along_the_lane_at_its_limit(egosim, rospy_client):
    client = rospy_client(egosim("--map", "straight", "--clock", "sim", "--rtf", "4"))
    client.subscribe(*EGO)
    assert set_ctrl_mode(client, AUTO)["ctrl_mode"] == AUTO
    since = client.received(EGO[0])
    trace: list[dict] = []
    while not trace or trace[-1]["header"]["stamp"] < trace[0]["header"]["stamp"] + 20.0:
        received = client.messages(EGO[0], since=since, count=1)
        since += len(received)
        trace += received
    speeds_kmh = [m["velocity"]["x"] * 3.6 for m in trace]
    # The straight map's limit is 100 km/h; the ego keeps to the middle of its lane.
    assert speeds_kmh[-1] == pytest.approx(100.0, abs=1.0)
    assert max(speeds_kmh) < 101.0
    assert max(abs(m["lateral_offset"]) for m in trace) < 0.1
    assert all(m["heading"] == pytest.approx(0.0, abs=0.5) for m in trace)

    assert set_ctrl_mode(client, EXTERNAL)["ctrl_mode"] == EXTERNAL
    # Back in external mode without a command, the autopilot's last command is dropped
    # (commands hold only while their input drives): the ego brakes.
    switched = client.next_message(EGO[0])["header"]["stamp"]
    status = client.next_message(EGO[0])
    while status["header"]["stamp"] < switched + 0.1:
        status = client.next_message(EGO[0])
    assert status["brake"] == pytest.approx(1.0)
