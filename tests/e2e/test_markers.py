"""/egosim/markers to a real rospy subscriber with Debian's visualization_msgs (what RViz
reads): the map first and latched, then egos, objects and lights at 10 Hz, in frame map."""

from __future__ import annotations

import json
import math
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from egosim.world.map import build_builtin_map
from tests.e2e.driver import RospyDriver
from tests.e2e.scenarios import write

pytestmark = pytest.mark.ros

PEER = Path(__file__).parent / "peers" / "marker_listener.py"
TOPIC = "/egosim/markers"
SET_LIGHT = ("/SetTrafficLight", "morai_msgs/SetTrafficLight")
EGO = ("/Ego_topic", "morai_msgs/EgoVehicleStatus")
RED, GREEN = 1, 16
LINE_LIST, CUBE, SPHERE_LIST, TEXT = 5, 1, 7, 9
OBSTACLE_XY = (-120.0, -275.25)

SCENE = f"""\
map: town
seed: 2
ego:
  start: {{lane: R1_E_1, s: 60.0}}
npcs:
  - start: {{lane: R2_E_1, s: 40.0}}
obstacles:
  - {{model: Cone, pose: {{x: {OBSTACLE_XY[0]}, y: {OBSTACLE_XY[1]}, heading_deg: 30.0}}}}
"""


def listen(spawn_ros: Callable[..., Any], uri: str, count: int) -> list[dict[str, Any]]:
    """`count` messages as Debian's rospy and visualization_msgs decode them."""
    listener = spawn_ros(["python", str(PEER), TOPIC, str(count), "30"], master_uri=uri)
    messages = [json.loads(listener.expect(r"^\{").string) for _ in range(count)]
    assert listener.wait(30) == 0, listener.stderr_text()
    return messages


def by_ns(message: dict[str, Any]) -> dict[str, list[dict[str, Any]]]:
    found: dict[str, list[dict[str, Any]]] = {}
    for marker in message["markers"]:
        found.setdefault(marker["ns"], []).append(marker)
    return found


def test_rviz_markers_of_the_town(
    egosim: Callable[..., Any],
    rospy_client: Callable[..., RospyDriver],
    spawn_ros: Callable[..., Any],
    tmp_path: Path,
) -> None:
    town = build_builtin_map("town")
    scenario = write(tmp_path, "scene.yaml", SCENE)
    simulator = egosim("--scenario", str(scenario), "--map", "town", "--clock", "sim")
    driver = rospy_client(simulator)
    driver.publish(*SET_LIGHT, {"trafficLightIndex": "TL2_W", "trafficLightStatus": RED})
    driver.publish(*SET_LIGHT, {"trafficLightIndex": "TL2_N", "trafficLightStatus": GREEN})
    driver.subscribe(*EGO)

    first = listen(spawn_ros, simulator.master_uri, 12)
    # A subscriber joining later gets the map first too: it is latched.
    late = listen(spawn_ros, simulator.master_uri, 2)
    ego = driver.messages(EGO[0], count=1)[-1]

    for messages in (first, late):
        static = by_ns(messages[0])
        assert messages[0]["latching"] == "1"
        assert {"roads", "lane_centres", "stop_lines", "crosswalks", "sidewalks"} <= set(static)
        assert {m["text"] for m in static["lane_ids"]} == {
            lane.id for lane in town.lanes.values() if not lane.is_junction
        }
        assert {m["text"] for m in static["light_ids"]} == set(town.traffic_lights)
        (road,) = static["roads"]
        assert road["type"] == LINE_LIST and road["scale"][0] == pytest.approx(3.5)
        segments = sum(len(lane.centerline) - 1 for lane in town.lanes.values())
        assert road["points"] == 2 * segments
        (stop_lines,) = static["stop_lines"]
        assert stop_lines["points"] == 2 * sum(
            lane.stop_line_s is not None for lane in town.lanes.values()
        )
        # What moves never comes back as part of the map, and the map never repeats.
        for message in messages[1:]:
            assert set(by_ns(message)) <= {"egos", "npcs", "pedestrians", "obstacles", "lights"}

    for message in first + late:
        assert {m["frame_id"] for m in message["markers"]} == {"map"}
        assert all(
            m["orientation"][3] != 0.0 or m["orientation"][2] != 0.0 for m in message["markers"]
        )

    scene = by_ns(first[-1])
    (ego_box,) = scene["egos"]
    assert ego_box["type"] == CUBE and ego_box["lifetime"] == pytest.approx(0.5)
    # The ego's box sits where /Ego_topic puts it (box centre vs rear axle: within a length).
    assert math.dist(ego_box["position"][:2], (ego["position"]["x"], ego["position"]["y"])) < 4.0
    (cone,) = scene["obstacles"]
    assert cone["position"][:2] == pytest.approx(OBSTACLE_XY, abs=1e-6)
    yaw = 2.0 * math.atan2(cone["orientation"][2], cone["orientation"][3])
    assert yaw == pytest.approx(math.radians(30.0), abs=1e-6)
    assert cone["position"][2] == pytest.approx(cone["scale"][2] / 2.0)
    assert len(scene["npcs"]) == 1

    (lights,) = scene["lights"]
    assert lights["type"] == SPHERE_LIST
    colours = {
        tuple(np.round(point[:2], 3)): colour
        for point, colour in zip(lights["points"], lights["colors"], strict=True)
    }
    assert len(colours) == len(town.traffic_lights)
    west = colours[tuple(np.round(town.traffic_lights["TL2_W"].position[:2], 3))]
    north = colours[tuple(np.round(town.traffic_lights["TL2_N"].position[:2], 3))]
    assert west[0] > 0.8 and west[1] < 0.2  # red
    assert north[1] > 0.8 and north[0] < 0.2  # green

    # 10 Hz on the simulator's clock.
    stamps = [message["markers"][0]["stamp"] for message in first[1:]]
    assert np.median(np.diff(stamps)) == pytest.approx(0.1, abs=0.011)
