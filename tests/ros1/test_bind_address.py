"""Servers listen where the node says it is (ROS_IP), not on every interface."""

from __future__ import annotations

import socket

import pytest

from egosim.ros1.network import NetworkConfig


@pytest.mark.parametrize(
    ("env", "bind"),
    [
        ({}, "127.0.0.1"),
        ({"ROS_IP": "10.20.30.40"}, "10.20.30.40"),
        ({"ROS_HOSTNAME": "localhost"}, "127.0.0.1"),
        ({"ROS_IP": "10.20.30.40", "EGOSIM_ROS_BIND": "0.0.0.0"}, "0.0.0.0"),
    ],
)
def test_servers_bind_the_advertised_address_unless_told_otherwise(env, bind) -> None:
    assert NetworkConfig.from_env(env).bind_host == bind


def test_a_node_on_a_second_loopback_address_listens_only_there(embedded_master, make_node):
    node = make_node("bound", master_uri=embedded_master.uri, env={"ROS_IP": "127.0.0.2"})
    host, port = node.tcpros_address
    assert host == "127.0.0.2"
    # Nothing answers on the first loopback address at that port.
    with pytest.raises(OSError), socket.create_connection(("127.0.0.1", port), timeout=2.0):
        pass
    with socket.create_connection(("127.0.0.2", port), timeout=2.0):
        pass
