"""Graph resource names (ROS wiki: Names) and command-line remapping."""

from __future__ import annotations

import pytest

from egosim.ros1 import InvalidNameError
from egosim.ros1.names import NameResolver, namespace_of, parse_argv, resolve


@pytest.mark.parametrize(
    ("name", "expected"),
    [
        ("/global", "/global"),
        ("relative", "/ns/relative"),
        ("a/b", "/ns/a/b"),
        ("~private", "/ns/node/private"),
        ("~", "/ns/node"),
        ("", "/ns"),
        ("/trailing/", "/trailing"),
    ],
)
def test_resolution(name, expected):
    assert resolve(name, "/ns/", "/ns/node") == expected


@pytest.mark.parametrize("name", ["1abc", "a b", "a//b", "_x", "a-b", "/x/~y"])
def test_invalid_names_are_refused(name):
    with pytest.raises(InvalidNameError):
        resolve(name, "/", "/node")


def test_namespace_of():
    assert namespace_of("/a/b/node") == "/a/b/"
    assert namespace_of("/node") == "/"


def test_argv_special_keys_remappings_and_private_params():
    args = parse_argv(
        ["prog", "__name:=sim", "__ns:=/cars", "chatter:=/talk", "_rate:=30", "_map:=[1, 2]"]
    )
    assert (args.name, args.namespace) == ("sim", "/cars")
    assert args.remappings == {"chatter": "/talk"}
    assert args.private_params == {"rate": 30, "map": [1, 2]}
    assert args.unparsed == ["prog"]


def test_remapping_applies_to_resolved_names():
    resolver = NameResolver("/cars/sim", {"chatter": "/talk", "~in": "out"})
    assert resolver.resolve("chatter") == "/talk"
    assert resolver.resolve("/cars/chatter") == "/talk"
    assert resolver.resolve("~in") == "/cars/out"
    assert resolver.resolve("other") == "/cars/other"


def test_node_name_and_remapping_from_argv(embedded_master, make_node):
    node = make_node(
        "egosim",
        argv=["__name:=sim", "__ns:=/cars", "Ego_topic:=/ego", "_rate:=50"],
        master_uri=embedded_master.uri,
    )
    assert node.name == "/cars/sim"
    assert node.resolve_name("Ego_topic") == "/ego"
    assert node.get_param("~rate") == 50
    assert node.get_param("/cars/sim/rate") == 50


def test_ros_namespace_environment(embedded_master, make_node):
    node = make_node("sim", master_uri=embedded_master.uri, env={"ROS_NAMESPACE": "/fleet"})
    assert node.name == "/fleet/sim"
    assert node.resolve_name("Ego_topic") == "/fleet/Ego_topic"
