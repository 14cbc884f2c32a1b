"""A network settings file with several mistakes reports all of them at once, file:line."""

from __future__ import annotations

import pytest

from egosim.bridge.protocol.network import parse_network_settings
from egosim.yamltext import YamlFileError

MISTAKES = """\
ego_input: Joystick
colour: blue
rows:
  ego_status: {name: "not a name", rate_hz: -3}
  collision: {enabled: maybe, volume: 11}
  teleporter: {}
sensors:
  seed: -1
  gps:
    mount: {x: far, yaw_deg: .nan}
  lidar:
    channels: 16.5
    horizontal_resolution_deg: 0
  sonar: {}
"""


def test_every_mistake_is_reported_with_its_line() -> None:
    with pytest.raises(YamlFileError) as caught:
        parse_network_settings(MISTAKES, "net.yaml")
    where = [(p.line, p.field) for p in caught.value.problems]
    assert where == [
        (1, "ego_input"),
        (2, "colour"),
        (4, "rows.ego_status.name"),
        (4, "rows.ego_status.rate_hz"),
        (5, "rows.collision.volume"),
        (5, "rows.collision.enabled"),
        (6, "rows.teleporter"),
        (8, "sensors.seed"),
        (10, "sensors.gps.mount.x"),
        (10, "sensors.gps.mount.yaw_deg"),
        (12, "sensors.lidar.channels"),
        (13, "sensors.lidar.horizontal_resolution_deg"),
        (14, "sensors.sonar"),
    ]
    lines = str(caught.value).splitlines()
    assert len(lines) == 13
    assert all(line.startswith("net.yaml:") for line in lines)
    assert "net.yaml:4: rows.ego_status.name: not a valid ROS name: 'not a name'" in lines


def test_one_mistake_is_one_line() -> None:
    with pytest.raises(YamlFileError) as caught:
        parse_network_settings("rows:\n  collision: {enabled: 2}\n", "net.yaml")
    assert str(caught.value) == "net.yaml:2: rows.collision.enabled: expected true or false"
