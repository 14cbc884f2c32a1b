"""Debian's rospy nodes and command-line tools against egosim's embedded master."""

from __future__ import annotations

import logging
import struct
import subprocess
import threading

import pytest
from rosbags.rosbag1 import Reader

from egosim.ros1 import ServiceType, TopicType
from tests.conftest import ROS_PYTHON
from tests.ros1.helpers import (
    PROFILE,
    STRING,
    Publishing,
    next_json,
    peer,
    string_bytes,
    string_text,
    wait_until,
)

pytestmark = pytest.mark.ros

EGO = PROFILE.message("morai_msgs/EgoVehicleStatus")


def run_tool(spawn_ros, master_uri: str, *args: str) -> str:
    """Run a ROS command-line tool to completion; its stdout."""
    process = spawn_ros(list(args), master_uri)
    code = process.wait()
    out = "".join(line + "\n" for line in iter_lines(process))
    assert code == 0, f"{args} exited {code}: {out}\n{process.stderr_text()}"
    return out


def iter_lines(process):
    process._reader.join()
    while not process.lines.empty():
        yield process.lines.get()


def test_rospy_talker_and_listener_through_embedded_master(embedded_master, spawn_ros):
    listener = spawn_ros(
        ["python", peer("listener.py"), "/chatter", "std_msgs/String"], embedded_master.uri
    )
    listener.expect("subscribed")
    spawn_ros(["python", peer("talker.py"), "/chatter", "std_msgs/String"], embedded_master.uri)
    first = next_json(listener, "n")
    assert first["msg"]["data"].startswith("hello ")
    assert first["callerid"] == "/talker"


def test_rostopic_list_info_echo_hz(embedded_master, spawn_ros, make_node):
    node = make_node("egosim", master_uri=embedded_master.uri)
    pub = node.advertise("/chatter", STRING)
    with Publishing(pub, lambda i: string_bytes(f"tick {i}"), rate_hz=20):
        assert "/chatter" in run_tool(spawn_ros, embedded_master.uri, "rostopic", "list").split()
        info = run_tool(spawn_ros, embedded_master.uri, "rostopic", "info", "/chatter")
        assert "Type: std_msgs/String" in info
        assert "/egosim" in info
        echo = run_tool(spawn_ros, embedded_master.uri, "rostopic", "echo", "-n", "1", "/chatter")
        assert 'data: "tick ' in echo
        hz = spawn_ros(["rostopic", "hz", "/chatter"], embedded_master.uri)
        rate = float(hz.expect(r"average rate: ([0-9.]+)").group(1))
        assert rate > 0


def test_rostopic_pub_reaches_egosim_subscriber(embedded_master, spawn_ros, make_node):
    node = make_node("egosim", master_uri=embedded_master.uri)
    received: list[str] = []
    node.subscribe("/cmd", STRING, lambda data, header: received.append(string_text(data)))
    run_tool(
        spawn_ros,
        embedded_master.uri,
        "rostopic",
        "pub",
        "-1",
        "/cmd",
        "std_msgs/String",
        "data: hi",
    )
    wait_until(lambda: received)
    assert received[0] == "hi"


def _roscpp_get_loggers() -> ServiceType:
    """roscpp/GetLoggers as Debian's Python package describes it (the peer's own md5s)."""
    probe = subprocess.run(
        [
            ROS_PYTHON,
            "-c",
            "import roscpp.srv as s; "
            "print(s.GetLoggers._md5sum, s.GetLoggersRequest._md5sum, "
            "s.GetLoggersResponse._md5sum)",
        ],
        capture_output=True,
        text=True,
        check=True,
    )
    service_md5, request_md5, response_md5 = probe.stdout.split()
    request = TopicType("roscpp/GetLoggersRequest", request_md5)
    response = TopicType("roscpp/GetLoggersResponse", response_md5)
    return ServiceType("roscpp/GetLoggers", service_md5, request, response)


def _loggers_response(loggers: list[tuple[str, str]]) -> bytes:
    def string(text: str) -> bytes:
        return struct.pack("<I", len(text)) + text.encode()

    return struct.pack("<I", len(loggers)) + b"".join(string(n) + string(lv) for n, lv in loggers)


def test_rosservice_list_type_call(embedded_master, spawn_ros, make_node):
    node = make_node("egosim", master_uri=embedded_master.uri)
    srv = _roscpp_get_loggers()
    node.advertise_service(
        "~get_loggers", srv, lambda request, header: _loggers_response([("egosim.world", "info")])
    )
    uri = embedded_master.uri
    assert "/egosim/get_loggers" in run_tool(spawn_ros, uri, "rosservice", "list").split()
    kind = run_tool(spawn_ros, uri, "rosservice", "type", "/egosim/get_loggers")
    assert kind.strip() == "roscpp/GetLoggers"
    reply = run_tool(spawn_ros, uri, "rosservice", "call", "/egosim/get_loggers")
    assert 'name: "egosim.world"' in reply
    assert 'level: "info"' in reply


def test_rosparam_set_get_list_and_updates(embedded_master, spawn_ros, make_node):
    node = make_node("egosim", master_uri=embedded_master.uri)
    updates: list[tuple[str, object]] = []
    updated = threading.Event()
    node.subscribe_param(
        "/sim/rate", lambda key, value: (updates.append((key, value)), updated.set())
    )
    uri = embedded_master.uri
    run_tool(spawn_ros, uri, "rosparam", "set", "/sim/rate", "30")
    assert node.get_param("/sim/rate") == 30
    assert updated.wait(30)
    assert updates[-1] == ("/sim/rate", 30)
    node.set_param("/sim/map", {"name": "town", "lanes": 3})
    assert run_tool(spawn_ros, uri, "rosparam", "get", "/sim/map/name").strip() == "town"
    tree = run_tool(spawn_ros, uri, "rosparam", "get", "/sim")
    assert "lanes: 3" in tree
    assert "rate: 30" in tree
    names = run_tool(spawn_ros, uri, "rosparam", "list").split()
    assert {"/sim/rate", "/sim/map/name", "/sim/map/lanes"} <= set(names)


def test_rosnode_list_info_kill(embedded_master, spawn_ros, make_node):
    node = make_node("egosim", master_uri=embedded_master.uri)
    reasons: list[str] = []
    node.on_shutdown(reasons.append)
    pub = node.advertise("/chatter", STRING)
    listener = spawn_ros(
        ["python", peer("listener.py"), "/chatter", "std_msgs/String"], embedded_master.uri
    )
    wait_until(lambda: pub.num_subscribers == 1)
    uri = embedded_master.uri
    assert "/egosim" in run_tool(spawn_ros, uri, "rosnode", "list").split()
    info = run_tool(spawn_ros, uri, "rosnode", "info", "/egosim")
    assert "Publications:" in info
    assert "/chatter [std_msgs/String]" in info
    assert "/listener" in info
    run_tool(spawn_ros, uri, "rosnode", "kill", "/egosim")
    assert node.wait_for_shutdown(30)
    assert reasons and "/rosnode" in reasons[0]
    publishers, _subscribers, _services = node.master.get_system_state()
    assert all("/egosim" not in nodes for _topic, nodes in publishers)
    listener.kill()


def test_rosbag_record_of_egosim_topic(embedded_master, spawn_ros, make_node, tmp_path):
    node = make_node("egosim", master_uri=embedded_master.uri)
    pub = node.advertise("/Ego_topic", EGO)
    bag = tmp_path / "ego.bag"
    sent = 25
    # With --limit the recorder closes the bag and exits by itself once it has written
    # `sent` messages, so an exit means every message arrived.
    recorder = spawn_ros(
        ["rosbag", "record", "--limit", str(sent), "-O", str(bag), "/Ego_topic"],
        embedded_master.uri,
    )
    wait_until(lambda: pub.num_subscribers == 1)
    for i in range(sent):
        pub.publish(EGO.serialize(EGO.new(unique_id=i)))
    assert recorder.wait() == 0
    with Reader(bag) as reader:
        connection = next(c for c in reader.connections if c.topic == "/Ego_topic")
        assert connection.msgtype == "morai_msgs/msg/EgoVehicleStatus"
        assert connection.digest == EGO.md5sum
        ids = [EGO.deserialize(raw).unique_id for _c, _t, raw in reader.messages()]
    assert ids == list(range(sent))


def test_python_logging_reaches_rosout(embedded_master, spawn_ros, make_node):
    node = make_node("egosim", master_uri=embedded_master.uri, rosout_logger="egosim.rosout_test")
    rosout = node.publisher("/rosout")
    assert rosout is not None
    listener = spawn_ros(
        ["python", peer("listener.py"), "/rosout", "rosgraph_msgs/Log"], embedded_master.uri
    )
    wait_until(lambda: rosout.num_subscribers == 1)
    logging.getLogger("egosim.rosout_test").warning("tyre pressure low")
    line = next_json(listener, "n")
    assert line["type"] == "rosgraph_msgs/Log"
    log = line["msg"]
    assert (log["name"], log["msg"], log["level"]) == ("/egosim", "tyre pressure low", 4)
    assert log["function"] == "test_python_logging_reaches_rosout"
