import math
from collections import Counter

import numpy as np
import pytest

from egosim.world.map import (
    BUILTIN_MAP_NAMES,
    LaneMap,
    MapError,
    build_builtin_map,
)


def _reachable(lanes: dict, start: str, forward: bool, lane_changes: bool = False) -> set[str]:
    seen, stack = {start}, [start]
    while stack:
        lane = lanes[stack.pop()]
        links = list(lane.successors if forward else lane.predecessors)
        if lane_changes:
            links += [n for n in (lane.left_neighbor, lane.right_neighbor) if n is not None]
        for nxt in links:
            if nxt not in seen:
                seen.add(nxt)
                stack.append(nxt)
    return seen


def test_every_town_lane_has_a_successor_and_predecessor(town: LaneMap) -> None:
    assert all(lane.successors and lane.predecessors for lane in town.lanes.values())


def test_town_is_strongly_connected_with_lane_changes(town: LaneMap) -> None:
    start = town.lane_ids[0]
    everything = set(town.lane_ids)
    assert _reachable(town.lanes, start, forward=True, lane_changes=True) == everything
    assert _reachable(town.lanes, start, forward=False, lane_changes=True) == everything


def test_following_successors_never_leads_into_a_cul_de_sac(town: LaneMap) -> None:
    # Every link lies on a cycle, so each connected part of the successor graph is
    # strongly connected: a car that only follows successors can return to any lane it left.
    for lane in town.lanes.values():
        for nxt in lane.successors:
            assert lane.id in _reachable(town.lanes, nxt, forward=True)


def test_links_are_symmetric_and_continuous(town: LaneMap) -> None:
    for lane in town.lanes.values():
        for nxt in lane.successors:
            assert lane.id in town.lanes[nxt].predecessors
            gap = lane.centerline[-1] - town.lanes[nxt].centerline[0]
            assert np.hypot(*gap[:2]) < 1e-9


def test_heading_is_smooth_across_links(town: LaneMap) -> None:
    # Connectors leave and join lanes tangentially; a sampled curve's end chord lags its
    # tangent by a small share of the turn.
    for lane in town.lanes.values():
        end_heading = town.pose_at(lane.id, lane.length)[3]
        for nxt in lane.successors:
            start_heading = town.pose_at(nxt, 0.0)[3]
            assert abs(math.remainder(start_heading - end_heading, math.tau)) < 0.06


def test_town_size_is_sensible(town: LaneMap) -> None:
    roads = [lane for lane in town.lanes.values() if not lane.is_junction]
    # 24 grid roads + 16 spurs to the ring + 16 ring sections, four lanes each.
    assert len(roads) == 56 * 4
    assert len(town.intersections) == 32
    total = sum(lane.length for lane in town.lanes.values())
    assert 30_000.0 < total < 60_000.0
    xmin, ymin, xmax, ymax = town.bounds()
    assert xmax - xmin == pytest.approx(814.0)
    assert ymax - ymin == pytest.approx(814.0)


def test_speed_limits(town: LaneMap) -> None:
    limits = sorted({round(lane.speed_limit * 3.6, 9) for lane in town.lanes.values()})
    assert limits == [50.0, 60.0]


def test_lights_govern_existing_lanes_with_stop_lines(town: LaneMap) -> None:
    for light in town.traffic_lights.values():
        assert light.lane_ids
        assert light.id in town.intersections[light.intersection_id].light_ids
        for lane_id in light.lane_ids:
            lane = town.lanes[lane_id]
            assert lane.traffic_light_ids == (light.id,)
            assert lane.stop_line_s is not None
            assert 0.0 < lane.stop_line_s < lane.length
            # The light stands beside the stop line and faces the approaching cars.
            x, y, _, heading = town.pose_at(lane_id, lane.stop_line_s)
            assert math.hypot(light.position[0] - x, light.position[1] - y) < 10.0
            assert abs(math.remainder(light.heading - heading, math.tau)) == pytest.approx(math.pi)
    governed = {lane.id for lane in town.lanes.values() if lane.traffic_light_ids}
    assert governed == {i for light in town.traffic_lights.values() for i in light.lane_ids}


def test_stop_lines_only_on_approaches(town: LaneMap) -> None:
    for lane in town.lanes.values():
        if lane.stop_line_s is not None:
            assert not lane.is_junction
            assert all(town.lanes[s].is_junction for s in lane.successors)


def test_the_town_shows_every_head_type_of_the_protocol(town: LaneMap) -> None:
    types = Counter(light.light_type for light in town.traffic_lights.values())
    assert set(types) == {0, 1, 2, 100}


def test_the_left_arrow_only_head_stands_over_an_approach_that_cannot_go_straight(
    town: LaneMap,
) -> None:
    (light,) = [t for t in town.traffic_lights.values() if t.light_type == 1]
    inner, outer = (town.lanes[lane_id] for lane_id in light.lane_ids)
    assert [("_left_" in s) for s in inner.successors] == [True]
    assert [("_right_" in s) for s in outer.successors] == [True]
    site = town.intersections[light.intersection_id]
    assert (light.id,) in site.approach_groups


def test_left_turn_heads_where_left_turns_exist(town: LaneMap) -> None:
    for light in town.traffic_lights.values():
        inner = town.lanes[light.lane_ids[0]]
        turns_left = any("_left_" in s for s in inner.successors)
        if light.light_type in (1, 2):
            assert turns_left
        if light.light_type == 0:
            assert not turns_left


def test_approach_groups_partition_the_lights(town: LaneMap) -> None:
    for site in town.intersections.values():
        grouped = [light for group in site.approach_groups for light in group]
        assert sorted(grouped) == sorted(site.light_ids)
        assert len(set(grouped)) == len(grouped)
        for group in site.approach_groups:
            # Lights in a group face opposite ways across the junction.
            if len(group) == 2:
                a, b = (town.traffic_lights[i].heading for i in group)
                assert abs(math.remainder(a - b, math.tau)) == pytest.approx(math.pi)


def test_crosswalks_lie_across_roads(town: LaneMap) -> None:
    arms = sum(len(site.light_ids) for site in town.intersections.values())
    assert len(town.crosswalks) == arms
    for walk in town.crosswalks.values():
        start, end = np.array(walk.start), np.array(walk.end)
        direction = (end - start) / np.hypot(*(end - start))
        crossed = set()
        for f in np.linspace(0.2, 0.8, 7):
            p = town.project(*(start + f * (end - start)))
            lane = town.lanes[p.lane_id]
            assert not lane.is_junction
            assert abs(p.lateral) < lane.widths[0] / 2 + 1e-9
            # Perpendicular to the traffic it crosses.
            assert (
                abs(math.cos(p.heading) * direction[0] + math.sin(p.heading) * direction[1]) < 1e-6
            )
            crossed.add(p.lane_id)
        assert len(crossed) == 4
        for end_point in (start, end):
            assert abs(town.project(*end_point).lateral) > 1.75


def test_sidewalks_stay_off_the_carriageway(town: LaneMap) -> None:
    assert len(town.sidewalks) == 9
    for walk in town.sidewalks.values():
        assert walk.points[0] == pytest.approx(walk.points[-1])
        dense = np.concatenate(
            [np.linspace(a, b, 50) for a, b in zip(walk.points[:-1], walk.points[1:], strict=True)]
        )
        projections = town.project_many(dense)
        assert np.all(np.abs(projections.lateral) > projections.width / 2)


def _distance_to_polyline(point: np.ndarray, line: np.ndarray) -> float:
    a, b = line[:-1, :2], line[1:, :2]
    t = np.clip(np.einsum("ij,ij->i", point - a, b - a) / np.sum((b - a) ** 2, axis=1), 0, 1)
    return float(np.min(np.hypot(*(a + t[:, None] * (b - a) - point).T)))


def test_lane_neighbours_are_same_direction_and_adjacent(town: LaneMap) -> None:
    for lane in town.lanes.values():
        if lane.right_neighbor is None:
            continue
        right = town.lanes[lane.right_neighbor]
        assert right.left_neighbor == lane.id
        middle = len(lane.centerline) // 2
        x, y, _, heading = town.pose_at(lane.id, float(lane.stations[middle]))
        # Parallel curves one lane width apart; on the inside of a bend the nearest point is a
        # mitred vertex, 3.5 / cos(half the 2 m chord's turn) away: under a millimetre more.
        gap = _distance_to_polyline(np.array([x, y]), right.centerline)
        assert gap == pytest.approx(3.5, abs=1e-3)
        p = town.project(x + 3.5 * math.sin(heading), y - 3.5 * math.cos(heading), heading)
        assert p.lane_id == right.id


def test_georeference_is_in_korea(town: LaneMap) -> None:
    lat, lon, _ = town.georef.local_to_geodetic(0.0, 0.0, 0.0)
    assert 33.0 < lat < 39.0
    assert 124.0 < lon < 132.0
    assert town.georef.utm_zone == 52


def test_builds_are_deterministic() -> None:
    for name in BUILTIN_MAP_NAMES:
        a, b = build_builtin_map(name), build_builtin_map(name)
        assert a.lane_ids == b.lane_ids
        assert a.lanes == b.lanes
        assert a.traffic_lights == b.traffic_lights
        assert a.intersections == b.intersections
        assert a.crosswalks == b.crosswalks
        assert a.sidewalks == b.sidewalks
        assert a.georef == b.georef


def test_unknown_map_name_is_refused() -> None:
    with pytest.raises(MapError, match="known maps: town, straight, loop"):
        build_builtin_map("atlantis")
    with pytest.raises(ValueError):
        build_builtin_map("")


def test_straight_map(straight: LaneMap) -> None:
    assert set(straight.lane_ids) == {"R1_E_1", "R1_E_2", "R1_W_1", "R1_W_2"}
    for lane in straight.lanes.values():
        assert lane.length == pytest.approx(1000.0)
        assert lane.speed_limit == pytest.approx(100 / 3.6)
    assert straight.lanes["R1_E_1"].right_neighbor == "R1_E_2"
    assert straight.lanes["R1_E_1"].left_neighbor is None
    assert not straight.traffic_lights


def test_loop_map_is_closed(loop: LaneMap) -> None:
    assert not loop.traffic_lights and not loop.intersections
    inner = _reachable(loop.lanes, "R1_N_1", forward=True)
    assert inner == {"R1_N_1", "R2_S_1"}
    lap = sum(loop.lanes[i].length for i in inner)
    assert lap == pytest.approx(2 * 75.0 + 2 * math.pi * 41.75, rel=1e-3)
