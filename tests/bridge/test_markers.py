"""/egosim/markers' messages built in process: the map's parts, boxes where the objects
are, lights in the colour they show; the row obeys the network settings."""

from __future__ import annotations

import math

import pytest

from egosim.bridge import BridgeContext, simulation_context
from egosim.bridge.protocol.network import parse_network_settings
from egosim.bridge.scene.markers import build_map_markers, yaw_quaternion
from egosim.msgs import get_profile
from egosim.sensors.rotation import quaternion_from_euler
from egosim.world import World
from egosim.world.map import build_builtin_map
from egosim.world.scenario import load_default_scenario, parse_scenario
from egosim.world.signals import GREEN, RED, YELLOW
from tests.bridge.built_rows import built

PROFILE = get_profile("26.r1")


def context_of(world: World) -> BridgeContext:
    return simulation_context(world)


def with_row(context: BridgeContext) -> tuple[BridgeContext, object]:
    return context, context.row("markers")


@pytest.fixture(scope="module")
def town_world() -> World:
    return World(build_builtin_map("town"), load_default_scenario())


def by_ns(message) -> dict[str, list]:
    found: dict[str, list] = {}
    for marker in message.markers:
        found.setdefault(marker.ns, []).append(marker)
    return found


def test_the_map_message_of_the_straight_road() -> None:
    lane_map = build_builtin_map("straight")
    scenario = parse_scenario("map: straight\nego: {start: {lane: R1_E_1, s: 5}}\n", "s.yaml")
    context, row = with_row(context_of(World(lane_map, scenario)))
    message_type = context.profile.message("visualization_msgs/MarkerArray")
    message = message_type.deserialize(build_map_markers(context, row))
    markers = by_ns(message)
    assert set(markers) == {"roads", "lane_centres", "lane_ids"}  # no lights, stops, walks
    (road,) = markers["roads"]
    assert road.scale.x == pytest.approx(3.5)
    ends = [(p.x, p.y) for p in road.points]
    assert (0.0, -1.75) in ends and (1000.0, -1.75) in ends
    assert sorted(m.text for m in markers["lane_ids"]) == sorted(lane_map.lanes)
    assert {m.header.frame_id for m in message.markers} == {"map"}
    assert all(m.pose.orientation.w == 1.0 for m in message.markers)


def test_scene_boxes_stand_where_the_objects_are(town_world: World) -> None:
    message = built(context_of(town_world), "markers")
    markers = by_ns(message)
    objects = town_world.objects()
    boxes = {(m.ns, m.id): m for ns in ("egos", "npcs", "pedestrians", "obstacles")
             for m in markers.get(ns, [])}  # fmt: skip
    assert len(boxes) == len(objects)
    for k, uid in enumerate(objects.unique_ids.tolist()):
        box = next(m for (ns, i), m in boxes.items() if i == uid)
        x, y, z = objects.positions[k]
        length, width, height = objects.sizes[k]
        assert (box.pose.position.x, box.pose.position.y) == pytest.approx((x, y))
        assert box.pose.position.z == pytest.approx(z + height / 2)
        assert (box.scale.x, box.scale.y, box.scale.z) == pytest.approx((length, width, height))
        yaw = 2 * math.atan2(box.pose.orientation.z, box.pose.orientation.w)
        assert math.remainder(yaw - objects.headings[k], math.tau) == pytest.approx(0, abs=1e-9)
        assert box.lifetime.nanosec == 500_000_000
    stamp = message.markers[0].header.stamp
    assert stamp.sec + stamp.nanosec * 1e-9 == pytest.approx(town_world.sim_time)


@pytest.mark.parametrize(("aspect", "rgb"), [(RED, "r"), (YELLOW, "rg"), (GREEN, "g")])
def test_lights_show_their_colour(town_world: World, aspect: int, rgb: str) -> None:
    town_world.signals.set_light("TL6_N", aspect)
    (lights,) = by_ns(built(context_of(town_world), "markers"))["lights"]
    index = list(town_world.signals.light_ids).index("TL6_N")
    point, colour = lights.points[index], lights.colors[index]
    assert (point.x, point.y) == pytest.approx(town_world.map.traffic_lights["TL6_N"].position[:2])
    lit = {
        name
        for name, value in zip("rgb", (colour.r, colour.g, colour.b), strict=True)
        if value > 0.7
    }
    assert lit == set(rgb)


def test_the_row_is_on_by_default_and_can_be_turned_off_renamed_rerated() -> None:
    assert parse_network_settings("{}\n", "n.yaml").row("markers").enabled
    settings = parse_network_settings(
        "rows:\n  markers: {name: /viz/scene, rate_hz: 5}\n", "n.yaml"
    )
    assert (settings.row("markers").name, settings.row("markers").rate_hz) == ("/viz/scene", 5)
    off = parse_network_settings("rows:\n  markers: {enabled: false}\n", "n.yaml")
    assert "markers" not in {row.key for row in off.enabled_rows()}


def test_a_heading_of_minus_zero_keeps_its_own_orientation() -> None:
    """Orientations are worked out once per heading; -0.0 equals 0.0 but turns z's sign."""
    for first, second in ((0.0, -0.0), (-0.0, 0.0)):
        yaw_quaternion(first)
        assert [math.copysign(1.0, q) for q in yaw_quaternion(second)] == [
            math.copysign(1.0, q) for q in quaternion_from_euler(0.0, 0.0, second)
        ]
