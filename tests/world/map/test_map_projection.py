import math

import numpy as np
import pytest

from egosim.world.map import LaneMap


def _left_normal(heading: float) -> np.ndarray:
    return np.array([-math.sin(heading), math.cos(heading)])


def _angle_between(a: float, b: float) -> float:
    return abs(math.remainder(a - b, math.tau))


@pytest.mark.parametrize("lane_id", ["R1_E_1", "R1_E_2", "R1_W_1", "R1_W_2"])
def test_centreline_point_projects_onto_its_lane(straight: LaneMap, lane_id: str) -> None:
    lane = straight.lanes[lane_id]
    for s in (0.5, 123.4, 500.0, 999.5):
        x, y, _, heading = straight.pose_at(lane_id, s)
        p = straight.project(x, y, heading)
        assert p.lane_id == lane_id
        assert p.s == pytest.approx(s, abs=1e-9)
        assert p.lateral == pytest.approx(0.0, abs=1e-9)
        assert p.width == lane.widths[0]


@pytest.mark.parametrize("offset", [-1.5, -0.7, 0.0, 0.4, 1.5])
def test_lateral_offset_and_boundary_distances(straight: LaneMap, offset: float) -> None:
    x, y, _, heading = straight.pose_at("R1_E_2", 300.0)
    point = np.array([x, y]) + offset * _left_normal(heading)
    p = straight.project(*point, heading=heading)
    assert p.lane_id == "R1_E_2"
    assert p.lateral == pytest.approx(offset, abs=1e-9)
    assert p.distance_left == pytest.approx(1.75 - offset, abs=1e-9)
    assert p.distance_right == pytest.approx(1.75 + offset, abs=1e-9)
    assert p.heading == pytest.approx(0.0, abs=1e-12)


def test_station_matches_polyline_arclength_on_curves(town: LaneMap) -> None:
    rng = np.random.default_rng(7)
    for lane_id in rng.choice([i for i in town.lane_ids if not town.lanes[i].is_junction], 40):
        lane = town.lanes[lane_id]
        k = int(rng.integers(0, len(lane.centerline) - 1))
        a, b = lane.centerline[k, :2], lane.centerline[k + 1, :2]
        point = a + 0.37 * (b - a)
        arclength = np.sum(np.hypot(*np.diff(lane.centerline[: k + 1, :2], axis=0).T))
        arclength += 0.37 * np.hypot(*(b - a))
        p = town.project(*point)
        assert p.lane_id == lane_id
        assert p.s == pytest.approx(arclength, abs=1e-6)
        assert p.lateral == pytest.approx(0.0, abs=1e-9)


def test_heading_hint_picks_direction_on_two_way_road(straight: LaneMap) -> None:
    # On the road's reference line the inner lanes of both directions are 1.75 m away.
    x, y = 400.0, 0.0
    east = straight.project(x, y, heading=0.1)
    west = straight.project(x, y, heading=math.pi - 0.1)
    assert east.lane_id == "R1_E_1"
    assert west.lane_id == "R1_W_1"
    assert east.lateral == pytest.approx(1.75)
    assert west.lateral == pytest.approx(1.75)


def test_wrong_side_without_hint_goes_to_the_nearest_lane(straight: LaneMap) -> None:
    assert straight.project(400.0, 1.0).lane_id == "R1_W_1"


def test_heading_hint_picks_connector_inside_junction(town: LaneMap) -> None:
    connectors = [i for i in town.lane_ids if town.lanes[i].is_junction]
    for lane_id in connectors:
        lane = town.lanes[lane_id]
        for fraction in (0.25, 0.5, 0.75):
            x, y, _, heading = town.pose_at(lane_id, fraction * lane.length)
            p = town.project(x, y, heading)
            assert p.lane_id == lane_id, (lane_id, fraction)
            assert p.lateral == pytest.approx(0.0, abs=1e-9)
            assert p.s == pytest.approx(fraction * lane.length, abs=1e-6)


def test_opposite_heading_never_wins_while_a_lane_points_the_right_way(town: LaneMap) -> None:
    lane_id = "R2_E_1"
    lane = town.lanes[lane_id]
    x, y, _, heading = town.pose_at(lane_id, lane.length / 2)
    left = np.array([x, y]) + 1.7 * _left_normal(heading)  # nearer to the west-bound lane
    p = town.project(*left, heading=heading)
    assert p.lane_id == lane_id
    assert _angle_between(p.heading, heading) < 1e-9


def test_pose_round_trip(town: LaneMap) -> None:
    rng = np.random.default_rng(11)
    for lane_id in rng.choice(town.lane_ids, 60):
        lane = town.lanes[lane_id]
        s = float(rng.uniform(0.05, 0.95) * lane.length)
        x, y, z, heading = town.pose_at(lane_id, s)
        p = town.project(x, y, heading)
        assert town.pose_at(p.lane_id, p.s)[:2] == pytest.approx((x, y), abs=1e-9)
        assert _angle_between(p.heading, heading) < 0.2
        assert z == 0.0


def test_pose_at_clamps_station(straight: LaneMap) -> None:
    assert straight.pose_at("R1_E_1", -5.0)[:2] == pytest.approx((0.0, -1.75))
    assert straight.pose_at("R1_E_1", 5000.0)[:2] == pytest.approx((1000.0, -1.75))


def test_poses_at_matches_pose_at(town: LaneMap) -> None:
    rng = np.random.default_rng(5)
    indices = rng.integers(0, len(town.lane_ids), 300)
    s = rng.uniform(-1.0, 1.1, 300) * town.lane_lengths[indices]
    poses = town.poses_at(indices, s)
    for k in range(0, 300, 7):
        assert tuple(poses[k]) == pytest.approx(town.pose_at(town.lane_ids[indices[k]], s[k]))


@pytest.mark.parametrize("with_headings", [False, True])
def test_project_many_equals_project(town: LaneMap, with_headings: bool) -> None:
    rng = np.random.default_rng(13)
    xmin, ymin, xmax, ymax = town.bounds()
    xy = rng.uniform((xmin - 50, ymin - 50), (xmax + 50, ymax + 50), size=(400, 2))
    headings = rng.uniform(-math.pi, math.pi, 400) if with_headings else None
    many = town.project_many(xy, headings)
    assert len(many) == 400
    for k in range(400):
        hint = None if headings is None else float(headings[k])
        assert many[k] == town.project(*xy[k], hint)


def test_far_point_projects_to_nearest_lane_end(straight: LaneMap) -> None:
    p = straight.project(5000.0, -1.75)
    assert p.lane_id == "R1_E_1"
    assert p.s == pytest.approx(1000.0)
    # Past a lane end the projection clamps to it; |lateral| is the distance to the end point.
    assert abs(p.lateral) == pytest.approx(4000.0)


def test_projection_distance_is_the_true_minimum(loop: LaneMap) -> None:
    rng = np.random.default_rng(17)
    dense = {i: np.linspace(0, lane.length, 2000) for i, lane in loop.lanes.items()}
    for xy in rng.uniform((-90, -50), (90, 50), size=(50, 2)):
        p = loop.project(*xy)
        best = min(
            float(
                np.min(
                    np.hypot(*(loop.poses_at(np.full(2000, loop.lane_index(i)), s)[:, :2] - xy).T)
                )
            )
            for i, s in dense.items()
        )
        assert abs(p.lateral) == pytest.approx(best, abs=0.05)


def test_grid_search_finds_the_nearest_centreline_anywhere(town: LaneMap) -> None:
    starts = np.concatenate([lane.centerline[:-1, :2] for lane in town.lanes.values()])
    ends = np.concatenate([lane.centerline[1:, :2] for lane in town.lanes.values()])
    rng = np.random.default_rng(19)
    xmin, ymin, xmax, ymax = town.bounds()
    xy = rng.uniform((xmin - 100, ymin - 100), (xmax + 100, ymax + 100), size=(300, 2))
    d = ends - starts
    rel = xy[:, None, :] - starts[None]
    t = np.clip(np.sum(rel * d, axis=2) / np.sum(d * d, axis=1), 0.0, 1.0)
    nearest = np.min(np.hypot(*np.moveaxis(rel - t[..., None] * d, 2, 0)), axis=1)
    assert np.abs(town.project_many(xy).lateral) == pytest.approx(nearest, abs=1e-9)
