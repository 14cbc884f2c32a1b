"""egosim nodes registered with Debian's rosmaster, talking to rospy nodes both ways."""

from __future__ import annotations

import pytest

from egosim.ros1 import ServiceError
from tests.ros1.helpers import (
    PROFILE,
    STRING,
    next_json,
    peer,
    string_bytes,
    string_text,
    wait_until,
    write_definition,
    write_service_spec,
)

pytestmark = pytest.mark.ros

EGO = PROFILE.message("morai_msgs/EgoVehicleStatus")
CTRL = PROFILE.message("morai_msgs/CtrlCmd")
EVENT_SRV = PROFILE.service("morai_msgs/MoraiEventCmdSrv")


def test_egosim_string_publisher_to_rospy_subscriber(rosmaster, spawn_ros, make_node):
    node = make_node("egosim_talker", master_uri=rosmaster, embedded_master="never")
    pub = node.advertise("/chatter", STRING)
    listener = spawn_ros(["python", peer("listener.py"), "/chatter", "std_msgs/String"], rosmaster)
    wait_until(lambda: pub.num_subscribers == 1)
    for i in range(5):
        pub.publish(string_bytes(f"message {i}"))
    for i in range(5):
        line = next_json(listener, "n")
        assert line["msg"] == {"data": f"message {i}"}
        assert line["md5"] == STRING.md5sum
        assert line["callerid"] == "/egosim_talker"


def test_egosim_morai_publisher_to_rospy_subscriber(rosmaster, spawn_ros, make_node, tmp_path):
    node = make_node("egosim_sim", master_uri=rosmaster, embedded_master="never")
    pub = node.advertise("/Ego_topic", EGO)
    listener = spawn_ros(
        [
            "python",
            peer("listener.py"),
            "/Ego_topic",
            EGO.name,
            "--definition",
            write_definition(tmp_path, EGO),
        ],
        rosmaster,
    )
    wait_until(lambda: pub.num_subscribers == 1)
    status = EGO.new(unique_id=7, velocity=EGO.new().velocity, heading=12.5, accel=0.25)
    status.velocity.x = 3.5
    pub.publish(EGO.serialize(status))
    line = next_json(listener, "n")
    assert line["type"] == "morai_msgs/EgoVehicleStatus"
    assert line["md5"] == EGO.md5sum
    assert line["msg"]["unique_id"] == 7
    assert line["msg"]["heading"] == 12.5
    assert line["msg"]["accel"] == 0.25
    assert line["msg"]["velocity"]["x"] == 3.5


def test_rospy_string_publisher_to_egosim_subscriber(rosmaster, spawn_ros, make_node):
    node = make_node("egosim_listener", master_uri=rosmaster, embedded_master="never")
    received: list[tuple[str, dict]] = []
    node.subscribe("/chatter", STRING, lambda data, header: received.append((data, header)))
    spawn_ros(["python", peer("talker.py"), "/chatter", "std_msgs/String"], rosmaster)
    wait_until(lambda: len(received) >= 3)
    texts = [string_text(data) for data, _ in received[:3]]
    first = int(texts[0].split()[1])
    assert texts == [f"hello {first + k}" for k in range(3)]
    header = received[0][1]
    assert header["md5sum"] == STRING.md5sum
    assert header["callerid"] == "/talker"
    assert header["type"] == "std_msgs/String"


def test_rospy_morai_publisher_to_egosim_subscriber(rosmaster, spawn_ros, make_node, tmp_path):
    node = make_node("egosim_sim", master_uri=rosmaster, embedded_master="never")
    received: list[bytes] = []
    node.subscribe("/ctrl_cmd", CTRL, lambda data, header: received.append(data))
    fields = '{"longlCmdType": 2, "velocity": 30.0, "front_steer": 0.1}'
    spawn_ros(
        [
            "python",
            peer("talker.py"),
            "/ctrl_cmd",
            CTRL.name,
            "--definition",
            write_definition(tmp_path, CTRL),
            "--fields",
            fields,
        ],
        rosmaster,
    )
    wait_until(lambda: received)
    command = CTRL.deserialize(received[0])
    assert (command.longlCmdType, command.velocity, command.front_steer) == (2, 30.0, 0.1)


def _echo_event(request: bytes, header) -> bytes:
    event = EVENT_SRV.request.deserialize(request).request
    event.gear = 4
    return EVENT_SRV.response.serialize(EVENT_SRV.response.new(response=event))


def test_rospy_client_calls_egosim_service(rosmaster, spawn_ros, make_node, tmp_path):
    node = make_node("egosim_sim", master_uri=rosmaster, embedded_master="never")
    node.advertise_service("/Service_MoraiEventCmd", EVENT_SRV, _echo_event)
    client = spawn_ros(
        [
            "python",
            peer("service_client.py"),
            "/Service_MoraiEventCmd",
            write_service_spec(tmp_path, EVENT_SRV),
            "--fields",
            '{"request": {"option": 3, "ctrl_mode": 3, "gear": 1, "set_pause": true}}',
            "--count",
            "3",
            "--persistent",
        ],
        rosmaster,
    )
    for _ in range(3):
        response = next_json(client, "response")["response"]["response"]
        assert (response["option"], response["ctrl_mode"], response["gear"]) == (3, 3, 4)
        assert response["set_pause"] is True


def test_egosim_handler_error_reaches_rospy_client(rosmaster, spawn_ros, make_node, tmp_path):
    def refuse(request: bytes, header) -> bytes:
        raise ValueError("scenario not loaded")

    node = make_node("egosim_sim", master_uri=rosmaster, embedded_master="never")
    node.advertise_service("/Service_MoraiEventCmd", EVENT_SRV, refuse)
    client = spawn_ros(
        [
            "python",
            peer("service_client.py"),
            "/Service_MoraiEventCmd",
            write_service_spec(tmp_path, EVENT_SRV),
        ],
        rosmaster,
    )
    assert "scenario not loaded" in next_json(client, "error")["error"]


def test_egosim_calls_rospy_service(rosmaster, spawn_ros, make_node, tmp_path):
    server = spawn_ros(
        [
            "python",
            peer("service_server.py"),
            "/remote_event",
            write_service_spec(tmp_path, EVENT_SRV),
        ],
        rosmaster,
    )
    server.expect("ready")
    node = make_node("egosim_client", master_uri=rosmaster, embedded_master="never")
    for persistent in (False, True):
        proxy = node.service_proxy("/remote_event", EVENT_SRV, persistent=persistent)
        proxy.wait_for_service(timeout=30)
        for option in (1, 2):
            request = EVENT_SRV.request.new(request=EVENT_SRV.request.new().request)
            request.request.option = option
            request.request.gear = 2
            reply = proxy.call(EVENT_SRV.request.serialize(request))
            event = EVENT_SRV.response.deserialize(reply).response
            assert (event.option, event.gear) == (option, 2)
        proxy.close()


def test_rospy_service_failure_raises_service_error(rosmaster, spawn_ros, make_node, tmp_path):
    server = spawn_ros(
        [
            "python",
            peer("service_server.py"),
            "/remote_event",
            write_service_spec(tmp_path, EVENT_SRV),
            "--fail",
        ],
        rosmaster,
    )
    server.expect("ready")
    node = make_node("egosim_client", master_uri=rosmaster, embedded_master="never")
    proxy = node.service_proxy("/remote_event", EVENT_SRV)
    with pytest.raises(ServiceError, match="deliberate failure"):
        proxy.call(EVENT_SRV.request.serialize(EVENT_SRV.request.new()))
