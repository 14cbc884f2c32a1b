"""Multi-ego: MultiEgoSetting adds, places, moves and removes egos; each additional ego
has its own namespaced status and command topics; camera_index picks /Ego_topic's ego."""

from __future__ import annotations

import xmlrpc.client

import pytest

pytestmark = pytest.mark.ros

EGO = ("/Ego_topic", "morai_msgs/EgoVehicleStatus")
EGO_1 = ("/ego_1/Ego_topic", "morai_msgs/EgoVehicleStatus")
CTRL_1 = ("/ego_1/ctrl_cmd", "morai_msgs/CtrlCmd")
SETTING = ("/ego_setting", "morai_msgs/MultiEgoSetting")
THROTTLE = {"longlCmdType": 1, "accel": 0.6, "brake": 0.0}
DRIVE, PARKING = 4, 1
AUTO, EXTERNAL = 16, 3


def second_ego(x: float, y: float, yaw_deg: float = 0.0, **fields) -> dict:
    """A MultiEgoSetting for two egos that places ego 1."""
    setting = {
        "number_of_ego_vehicle": 2,
        "camera_index": 0,
        "ego_index": [1],
        "global_position_x": [x],
        "global_position_y": [y],
        "global_position_z": [0.0],
        "global_roll": [0.0],
        "global_pitch": [0.0],
        "global_yaw": [yaw_deg],
    }
    return {**setting, **fields}


def registered_publishers(master_uri: str) -> set[str]:
    code, _, (publishers, _, _) = xmlrpc.client.ServerProxy(master_uri).getSystemState("/t")
    assert code == 1
    return {topic for topic, nodes in publishers if "/egosim" in nodes}


def wait_for(client, topic: str, check, tries: int = 200) -> dict:
    for _ in range(tries):
        message = client.next_message(topic)
        if check(message):
            return message
    raise AssertionError(f"no matching message on {topic}")


@pytest.fixture
def two_egos(egosim, rospy_client):
    simulator = egosim("--map", "straight")
    client = rospy_client(simulator)
    client.subscribe(*EGO)
    client.publish(*SETTING, second_ego(150.0, -5.25, velocity=[0.0], gear=[DRIVE]))
    for _ in range(100):
        if "/ego_1/Ego_topic" in registered_publishers(simulator.master_uri):
            break
        client.next_message(EGO[0])
    client.subscribe(*EGO_1)
    return simulator, client


def test_an_added_ego_reports_its_pose_and_obeys_its_own_ctrl_cmd(two_egos):
    _, client = two_egos
    main = client.next_message(EGO[0])
    other = client.next_message(EGO_1[0])
    assert other["unique_id"] != main["unique_id"]
    assert (other["position"]["x"], other["position"]["y"]) == pytest.approx((150.0, -5.25))
    assert other["heading"] == pytest.approx(0.0)

    client.stream(*CTRL_1, THROTTLE, rate=50)
    moving = wait_for(client, EGO_1[0], lambda m: m["velocity"]["x"] > 1.0)
    client.stop_stream(CTRL_1[0])
    assert moving["position"]["x"] > 150.0
    assert moving["accel"] == pytest.approx(0.6, abs=1e-6)
    still = client.next_message(EGO[0])
    assert still["velocity"]["x"] == pytest.approx(0.0, abs=0.01)
    assert still["position"] == main["position"]


def test_camera_index_selects_the_ego_on_ego_topic(two_egos):
    _, client = two_egos
    other_id = client.next_message(EGO_1[0])["unique_id"]
    client.publish(*SETTING, {**second_ego(150.0, -5.25), "camera_index": 1})
    shown = wait_for(client, EGO[0], lambda m: m["unique_id"] == other_id)
    assert shown["position"]["x"] == pytest.approx(150.0)


def test_moving_setting_gear_and_auto_mode_of_an_ego(two_egos):
    _, client = two_egos
    client.publish(
        *SETTING, second_ego(300.0, -1.75, velocity=[36.0], gear=[DRIVE], ctrl_mode=[AUTO])
    )
    driven = wait_for(client, EGO_1[0], lambda m: m["position"]["x"] > 300.0)
    assert driven["position"]["y"] == pytest.approx(-1.75, abs=0.2)
    # The autopilot drives it on at the lane's 100 km/h, with no command sent.
    faster = wait_for(client, EGO_1[0], lambda m: m["velocity"]["x"] > 15.0)
    assert abs(faster["lateral_offset"]) < 0.2

    parking = second_ego(400.0, -1.75, velocity=[0.0], gear=[PARKING], ctrl_mode=[EXTERNAL])
    client.publish(*SETTING, parking)
    wait_for(client, EGO_1[0], lambda m: m["position"]["x"] == pytest.approx(400.0))
    # In park, throttle does not move it.
    client.stream(*CTRL_1, THROTTLE, rate=50)
    later = [client.next_message(EGO_1[0]) for _ in range(30)][-1]
    client.stop_stream(CTRL_1[0])
    assert later["accel"] == pytest.approx(0.6, abs=1e-6)
    assert later["position"]["x"] == pytest.approx(400.0)
    assert later["velocity"]["x"] == pytest.approx(0.0)


def test_reducing_the_number_of_egos_withdraws_their_topics(two_egos):
    simulator, client = two_egos
    assert {"/ego_1/Ego_topic"} <= registered_publishers(simulator.master_uri)
    client.publish(*SETTING, {"number_of_ego_vehicle": 1, "camera_index": 0})
    for _ in range(200):
        if "/ego_1/Ego_topic" not in registered_publishers(simulator.master_uri):
            break
        client.next_message(EGO[0])
    assert "/ego_1/Ego_topic" not in registered_publishers(simulator.master_uri)
    assert "/Ego_topic" in registered_publishers(simulator.master_uri)


def test_a_setting_with_mismatched_arrays_changes_nothing(two_egos):
    simulator, client = two_egos
    before = client.next_message(EGO_1[0])
    bad = {**second_ego(500.0, -1.75), "global_position_y": [-1.75, 2.0]}
    client.publish(*SETTING, bad)
    client.publish(*SETTING, {**second_ego(150.0, -5.25), "number_of_ego_vehicle": 0})
    later = [client.next_message(EGO_1[0]) for _ in range(30)][-1]
    assert later["position"] == before["position"]
    assert simulator.process.popen.poll() is None
