"""A restarted master learns everything again: Debian's rosmaster killed and restarted."""

from __future__ import annotations

import xmlrpc.client

import pytest

from tests.conftest import free_port, wait_for_master
from tests.debian_ros import missing_ros_reason
from tests.ros1.helpers import PROFILE, STRING, wait_until

pytestmark = pytest.mark.ros

EVENT_SRV = PROFILE.service("morai_msgs/MoraiEventCmdSrv")
REREGISTER_TIMEOUT_S = 10.0


def system_state(uri: str) -> tuple[dict, dict, dict]:
    code, _, (publishers, subscribers, services) = xmlrpc.client.ServerProxy(uri).getSystemState(
        "/test"
    )
    assert code == 1
    return (
        {topic: nodes for topic, nodes in publishers},
        {topic: nodes for topic, nodes in subscribers},
        {service: nodes for service, nodes in services},
    )


def knows_the_node(uri: str) -> bool:
    publishers, subscribers, services = system_state(uri)
    code, _, value = xmlrpc.client.ServerProxy(uri).getParam("/test", "/watched/rate")
    return (
        "/watched" in publishers.get("/chatter", [])
        and "/watched" in subscribers.get("/orders", [])
        and "/watched" in services.get("/echo", [])
        and code == 1
        and value == 50
    )


def test_a_node_registers_everything_with_a_restarted_master(spawn_ros, make_node, caplog):
    if reason := missing_ros_reason():
        pytest.skip(reason)
    port = free_port()
    uri = f"http://127.0.0.1:{port}/"
    command = ["/usr/bin/rosmaster", "--core", "-p", str(port)]
    first = spawn_ros(command, ROS_IP="127.0.0.1")
    wait_for_master(uri)
    node = make_node("watched", master_uri=uri, embedded_master="never")
    node.advertise("/chatter", STRING)
    node.subscribe("/orders", STRING, lambda data, header: None)
    node.advertise_service("/echo", EVENT_SRV, lambda request, header: request)
    node.set_param("~rate", 50)
    assert knows_the_node(uri)

    first.kill()
    spawn_ros(command, ROS_IP="127.0.0.1")
    wait_for_master(uri)
    wait_until(lambda: knows_the_node(uri), timeout=REREGISTER_TIMEOUT_S)
    assert any("registered again" in r.getMessage() for r in caplog.records)
