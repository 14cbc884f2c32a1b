"""World -> what the page draws: the map once, then frames (SI units, plain JSON)."""

from __future__ import annotations

import base64
import json
import math

import numpy as np
import pytest

from egosim.bridge.context import BridgeContext
from egosim.view.messages import SensorImage
from egosim.view.snapshot import COLLISION_FLASH_S, FrameInfo, capture_frame, encode, map_snapshot
from egosim.world.map.markings import STOP_LINE_WIDTH_M, MarkingKind, map_markings
from egosim.world.signals import RED
from egosim.world.traffic import ObjectType
from egosim.world.vehicle import Pose

from .conftest import STRAIGHT, TOWN

INFO = FrameInfo(clock_mode="real", real_time_factor=1.0, controls_enabled=True)


def frame_json(context: BridgeContext, **options) -> dict:
    return json.loads(encode(capture_frame(context, INFO, **options)))


def test_lane_outlines_lie_half_a_width_either_side_of_the_centreline() -> None:
    snapshot = map_snapshot(STRAIGHT)
    lane = STRAIGHT.lane(STRAIGHT.lane_ids[0])
    outline = np.array(next(s["outline"] for s in snapshot["lanes"] if s["id"] == lane.id))
    left, right = outline[: len(outline) // 2], outline[len(outline) // 2 :][::-1]
    centre = lane.centerline[:, :2]
    assert np.allclose(np.hypot(*(left - centre).T), lane.widths / 2, atol=0.01)
    assert np.allclose(np.hypot(*(right - centre).T), lane.widths / 2, atol=0.01)
    heading = math.atan2(*(centre[1] - centre[0])[::-1])
    to_left = left[0] - centre[0]
    # The left edge is on the left of the direction of travel.
    assert math.cos(heading) * to_left[1] - math.sin(heading) * to_left[0] > 0


def test_the_page_paints_what_the_cameras_see() -> None:
    snapshot = json.loads(encode(map_snapshot(STRAIGHT)))
    paint = [m for m in map_markings(STRAIGHT) if m.kind is MarkingKind.LANE_LINE]
    assert len(snapshot["markings"]) == len(paint)
    for drawn, marking in zip(snapshot["markings"], paint, strict=True):
        assert np.allclose(drawn["points"], marking.points[:, :2], atol=0.01)
        assert drawn["color"] == marking.color.value
        assert drawn["double"] == (len(marking.lines) == 2)
    lanes = list(STRAIGHT.lanes.values())
    styles = sorted((m["color"], m["style"], m["double"]) for m in snapshot["markings"])
    # Dashes between lanes of one direction, one double yellow line between directions.
    assert styles.count(("white", "dashed", False)) == sum(
        lane.right_neighbor is not None for lane in lanes
    )
    assert styles.count(("yellow", "solid", True)) == 1
    assert snapshot["stop_lines"] == []


def test_stop_lines_cross_their_lane_just_before_the_stop_station() -> None:
    snapshot = map_snapshot(TOWN)
    stopping = [lane for lane in TOWN.lanes.values() if lane.stop_line_s is not None]
    assert len(snapshot["stop_lines"]) == len(stopping)
    lane = stopping[0]
    (x0, y0), (x1, y1) = snapshot["stop_lines"][0]
    # The paint's far edge is on the stop station: its centre half a line width before.
    s = lane.stop_line_s - STOP_LINE_WIDTH_M / 2
    x, y, _, heading = TOWN.pose_at(lane.id, s)
    assert math.isclose((x0 + x1) / 2, x, abs_tol=0.01)
    assert math.isclose((y0 + y1) / 2, y, abs_tol=0.01)
    width = float(np.interp(s, lane.stations, lane.widths))
    assert math.isclose(math.hypot(x1 - x0, y1 - y0), width, abs_tol=0.02)
    # Across the lane: perpendicular to its heading.
    assert abs(math.cos(heading) * (x1 - x0) + math.sin(heading) * (y1 - y0)) < 0.02


def test_map_lists_every_light_crosswalk_junction_and_the_world_codes() -> None:
    snapshot = map_snapshot(TOWN)
    assert {light["id"] for light in snapshot["lights"]} == set(TOWN.traffic_lights)
    assert len(snapshot["crosswalks"]) == len(TOWN.crosswalks)
    assert len(snapshot["junctions"]) == len(TOWN.intersections)
    assert snapshot["aspect_bits"]["red"] == RED
    assert snapshot["object_kinds"]["pedestrian"] == ObjectType.PEDESTRIAN


def test_frame_shows_the_ego_where_the_world_has_it(town: BridgeContext) -> None:
    world = town.world
    for _ in range(50):
        world.step(0.01)
    frame = frame_json(town)
    ego = frame["egos"][0]
    status = world.ego_status(0)
    assert ego["id"] == world.egos[0].unique_id
    assert math.isclose(ego["x"], status.pose.x, abs_tol=0.005)
    assert math.isclose(ego["y"], status.pose.y, abs_tol=0.005)
    assert math.isclose(ego["yaw"], status.pose.yaw, abs_tol=0.0005)
    assert ego["lane_id"] == world.ego_lane_state(0).lane_id
    assert frame["sim_time"] == pytest.approx(0.5)


def test_frame_lists_the_other_objects_with_their_speeds(town: BridgeContext) -> None:
    world = town.world
    for _ in range(100):
        world.step(0.01)
    frame = frame_json(town)
    table = world.objects()
    others = table.object_types != ObjectType.EGO
    assert frame["objects"]["id"] == table.unique_ids[others].tolist()
    speeds = np.hypot(table.velocities[others, 0], table.velocities[others, 1])
    assert np.allclose(frame["objects"]["speed"], speeds, atol=0.005)
    assert max(frame["objects"]["speed"]) > 0  # the town's NPCs drive off


def test_frame_carries_every_light_aspect(town: BridgeContext) -> None:
    light_id = town.world.signals.light_ids[0]
    town.world.signals.set_light(light_id, RED)
    frame = frame_json(town)
    lights = map_snapshot(TOWN)["lights"]
    assert [light["id"] for light in lights] == list(town.world.signals.light_ids)
    assert frame["light_aspects"][0] == RED
    assert frame["light_aspects"] == town.world.signals.aspects().tolist()


def test_a_collision_flashes_for_a_while_where_it_happened(straight: BridgeContext) -> None:
    world = straight.world
    ego = world.ego_status(0).pose
    obstacle = world.add_object("Barrier", (ego.x + 3.0, ego.y, 0.0), 0.0)
    world.egos[0].vehicle.teleport(Pose(ego.x, ego.y, ego.z, yaw=ego.yaw), speed=10.0)
    for _ in range(100):
        world.step(0.01)
        if world.ego_collision_log:
            break
    assert world.ego_collision_log, "the ego reached the barrier"
    flash = frame_json(straight)["collisions"]
    assert len(flash) == 1
    hit = world.ego_collision_log[0].other
    assert hit.unique_id == obstacle
    assert math.isclose(flash[0]["x"], hit.position[0], abs_tol=0.01)
    world.egos[0].vehicle.teleport(Pose(ego.x - 50, ego.y, ego.z, yaw=ego.yaw))
    for _ in range(round(COLLISION_FLASH_S / 0.01) + 5):
        world.step(0.01)
    assert frame_json(straight)["collisions"] == []


def test_frame_has_lidar_points_and_sensor_images_when_given(straight: BridgeContext) -> None:
    points = np.array([[1.234567, -2.0, 0.5], [3.0, 4.0, 0.1]])
    image = SensorImage("front", "image/jpeg", b"\xff\xd8jpeg", 1.5)
    frame = frame_json(straight, lidar=points, images=[lambda: image, lambda: None])
    assert frame["lidar"] == [1.23, -2.0, 3.0, 4.0]
    data = base64.b64encode(b"\xff\xd8jpeg").decode()
    assert frame["images"] == [{"name": "front", "mime": "image/jpeg", "data": data, "stamp": 1.5}]
    assert frame_json(straight)["lidar"] is None


def test_encoding_is_compact_json_in_si_units(town: BridgeContext) -> None:
    text = encode(capture_frame(town, INFO))
    frame = json.loads(text)
    assert " " not in text.split('"model"')[0]
    assert frame["egos"][0]["speed"] == 0.0  # m/s, not km/h
    assert frame["clock_mode"] == "real"
    assert frame["sync_frame"] is None
    assert frame["replay"] is None
    assert len(text) < 8000
