"""Clients compiled against any morai_msgs release drive the same simulator at once."""

from __future__ import annotations

import pytest

from egosim.msgs import get_profile
from tests.e2e.probe import handshake

pytestmark = pytest.mark.ros

EGO = ("/Ego_topic", "morai_msgs/EgoVehicleStatus")
OBJECTS = ("/Object_topic", "morai_msgs/ObjectStatusList")
CTRL = ("/ctrl_cmd", "morai_msgs/CtrlCmd")
STEER_FIELD = {"26.r1": "front_steer", "24.r2": "steering", "2021.08": "steering"}
STEER_STATUS = {"26.r1": "front_steer_angle", "24.r2": "wheel_angle", "2021.08": "wheel_angle"}
RELEASES = ("26.r1", "24.r2", "2021.08")


@pytest.fixture(scope="module")
def straight(module_egosim):
    """One simulator on the straight map for the tests that call services and handshake:
    a gear set to 2 by each release, nothing else changed."""
    return module_egosim("--map", "straight")


@pytest.mark.parametrize("release", RELEASES)
def test_client_of_a_release_steers_and_reads_the_ego(egosim, rospy_client, release) -> None:
    client = rospy_client(egosim("--map", "straight"), profile=release)
    client.subscribe(*EGO)
    command = {"longlCmdType": 2, "velocity": 20.0, STEER_FIELD[release]: 0.1}
    client.stream(*CTRL, command, rate=50)
    status = [client.next_message(EGO[0]) for _ in range(100)][-1]
    client.stop_stream(CTRL[0])
    assert status["velocity"]["x"] > 1.0
    assert status[STEER_STATUS[release]] == pytest.approx(5.7296, abs=0.01)
    assert status["velocity"]["y"] != 0.0 or status["heading"] != 0.0


def test_three_releases_at_once_see_the_same_world(egosim, rospy_client) -> None:
    simulator = egosim()
    clients = {release: rospy_client(simulator, profile=release) for release in RELEASES}
    for client in clients.values():
        client.subscribe(*EGO)
        client.subscribe(*OBJECTS)
    clients["26.r1"].stream(*CTRL, {"longlCmdType": 2, "velocity": 15.0}, rate=50)
    seen = {r: c.messages(EGO[0], count=150) for r, c in clients.items()}
    clients["26.r1"].stop_stream(CTRL[0])
    by_stamp = [{m["header"]["stamp"]: m["position"] for m in msgs} for msgs in seen.values()]
    common = set(by_stamp[0]) & set(by_stamp[1]) & set(by_stamp[2])
    assert len(common) > 50
    for stamp in common:
        assert by_stamp[0][stamp] == by_stamp[1][stamp] == by_stamp[2][stamp]
    objects = {r: c.next_message(OBJECTS[0])["num_of_npcs"] for r, c in clients.items()}
    assert set(objects.values()) == {8}


@pytest.mark.parametrize("release", RELEASES)
def test_services_answer_each_release_in_its_own(straight, rospy_client, release) -> None:
    client = rospy_client(straight, profile=release)
    reply = client.call(
        "/Service_MoraiEventCmd",
        "morai_msgs/MoraiEventCmdSrv",
        {"request": {"option": 2, "gear": 2}},
    )
    assert reply["response"]["gear"] == 2
    spec = client.call(
        "/Service_MoraiMapSpec", "morai_msgs/MoraiMapSpecSrv", {"request": {"load_map_data": True}}
    )
    assert spec["response"]["utm_num"] == 52


def test_unknown_md5_is_refused_naming_the_accepted_ones(straight) -> None:
    reply = handshake(
        straight.master_uri,
        "/Ego_topic",
        "morai_msgs/EgoVehicleStatus",
        "0123456789abcdef0123456789abcdef",
    )
    for release in RELEASES:
        md5sum = get_profile(release).message("morai_msgs/EgoVehicleStatus").md5sum
        assert f"{md5sum} ({release})" in reply["error"]


@pytest.mark.parametrize("release", RELEASES)
def test_sync_mode_for_each_release(egosim, rospy_client, release) -> None:
    client = rospy_client(egosim("--map", "straight", "--clock", "sync"), profile=release)
    start = {"user_id": "planner", "start_sync_mode": True}
    if release != "2021.08":
        start["time_step"] = 10
    frame = client.call("/SyncModeCmd", "morai_msgs/MoraiSyncModeCmdSrv", {"request": start})[
        "response"
    ]["frame"]
    command = {"longlCmdType": 1, "accel": 0.8, STEER_FIELD[release]: 0.05}
    for k in range(1, 201):
        tick = {"user_id": "planner", "frame": frame + k}
        if release == "2021.08":
            tick["command"] = command  # 2021.08 sends the command with the tick
        else:
            client.call(
                "/SyncModeCtrlCmd",
                "morai_msgs/MoraiSyncModeCtrlCmdSrv",
                {"request": {"frame": frame + k, "command": command}},
            )
        reply = client.call(
            "/SyncModeWaitForTick", "morai_msgs/MoraiWaitForTickSrv", {"request": tick}
        )["response"]
        assert reply["tick_status"] is True
    status = reply["vehicle_status"]
    assert reply["frame"] == frame + 200
    assert status["velocity"]["x"] > 1.0
    assert status[STEER_STATUS[release]] == pytest.approx(2.8648, abs=0.01)
