import numpy as np
import pytest

from egosim.world.map import LaneMap


def _length(path: np.ndarray) -> float:
    return float(np.sum(np.hypot(*np.diff(path, axis=0).T)))


def test_lookahead_within_one_lane(straight: LaneMap) -> None:
    path = straight.lookahead("R1_E_1", 100.0, 50.0)
    assert path[0] == pytest.approx((100.0, -1.75))
    assert path[-1] == pytest.approx((150.0, -1.75))
    assert _length(path) == pytest.approx(50.0)


def test_lookahead_stops_at_a_dead_end(straight: LaneMap) -> None:
    path = straight.lookahead("R1_W_2", 900.0, 300.0)
    assert path[-1] == pytest.approx((0.0, 5.25))
    assert _length(path) == pytest.approx(100.0)


def test_lookahead_goes_round_the_loop(loop: LaneMap) -> None:
    lap = loop.lanes["R1_N_1"].length + loop.lanes["R2_S_1"].length
    path = loop.lookahead("R1_N_1", 10.0, lap)
    assert _length(path) == pytest.approx(lap, rel=1e-9)
    assert path[-1] == pytest.approx(path[0], abs=1e-9)


def test_lookahead_follows_route_through_junction(town: LaneMap) -> None:
    # R2 runs east from junction 2 to junction 3; turn left (north) at junction 3.
    lane = town.lanes["R2_E_1"]
    route = ["J3_W_N_left_1"]
    path = town.lookahead("R2_E_1", lane.length - 10.0, 60.0, route)
    assert _length(path) == pytest.approx(60.0, rel=1e-9)
    end = town.project(*path[-1])
    assert end.lane_id == town.lanes["J3_W_N_left_1"].successors[0]
    assert end.lateral == pytest.approx(0.0, abs=1e-9)
    assert path[-1][0] == pytest.approx(90.0 + 1.75)


def test_lookahead_without_route_takes_first_successor(town: LaneMap) -> None:
    lane = town.lanes["R2_E_1"]
    path = town.lookahead("R2_E_1", lane.length - 5.0, 20.0)
    first = lane.successors[0]
    assert town.project(*path[-1]).lane_id == first
    assert _length(path) == pytest.approx(20.0, rel=1e-9)


def test_lookahead_points_lie_on_centrelines(town: LaneMap) -> None:
    path = town.lookahead("R13_N_2", 3.0, 700.0)
    many = town.project_many(path)
    assert np.max(np.abs(many.lateral)) < 1e-6
