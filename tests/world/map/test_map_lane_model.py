import math

import numpy as np
import pytest

from egosim.world.map import (
    Lane,
    LaneMap,
    MapGeometryError,
    Sidewalk,
    UnknownLaneError,
)
from egosim.world.map.builtin_origin import BUILTIN_GEOREF


def _lane(lane_id: str = "A", **links: object) -> Lane:
    points = np.array([[0.0, 0.0, 0.0], [3.0, 4.0, 0.0], [3.0, 10.0, 1.0]])
    return Lane(lane_id, points, np.array([3.0, 3.5, 4.0]), 10.0, **links)


def _map(*lanes: Lane) -> LaneMap:
    return LaneMap("t", lanes, (), (), (), (), BUILTIN_GEOREF)


def test_stations_and_length_are_planar_arclength() -> None:
    lane = _lane()
    assert lane.stations == pytest.approx([0.0, 5.0, 11.0])
    assert lane.length == pytest.approx(11.0)


def test_lane_arrays_are_read_only() -> None:
    lane = _lane()
    with pytest.raises(ValueError):
        lane.centerline[0, 0] = 1.0


def test_two_column_centreline_lies_at_zero_height() -> None:
    lane = Lane("B", np.array([[0.0, 0.0], [1.0, 0.0]]), np.array([3.0, 3.0]), 5.0)
    assert lane.centerline.shape == (2, 3)
    assert np.all(lane.centerline[:, 2] == 0.0)


@pytest.mark.parametrize(
    ("points", "widths"),
    [
        ([[0.0, 0.0, 0.0]], [3.0]),
        ([[0.0, 0.0, 0.0], [0.0, 0.0, 0.0]], [3.0, 3.0]),
        ([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]], [3.0, -1.0]),
        ([[0.0, 0.0, 0.0], [np.nan, 0.0, 0.0]], [3.0, 3.0]),
    ],
)
def test_bad_geometry_is_refused(points: list, widths: list) -> None:
    with pytest.raises(MapGeometryError):
        Lane("bad", np.array(points), np.array(widths), 10.0)


def test_stop_line_must_lie_on_the_lane() -> None:
    with pytest.raises(MapGeometryError):
        _lane(stop_line_s=12.0)


def test_lane_equality_compares_geometry() -> None:
    assert _lane() == _lane()
    assert _lane() != _lane(successors=("A",))
    walk = Sidewalk("w", np.array([[0.0, 0.0], [1.0, 1.0]]))
    assert walk == Sidewalk("w", np.array([[0.0, 0.0], [1.0, 1.0]]))


def test_map_refuses_dangling_links_and_repeated_ids() -> None:
    with pytest.raises(MapGeometryError):
        _map(_lane(successors=("nowhere",)))
    with pytest.raises(MapGeometryError):
        _map(_lane(), _lane())
    with pytest.raises(MapGeometryError):
        _map(_lane(traffic_light_ids=("TL1_N",)))


def test_unknown_lane_lookups_raise() -> None:
    lane_map = _map(_lane())
    with pytest.raises(UnknownLaneError):
        lane_map.lane_index("B")
    with pytest.raises(KeyError):
        lane_map.pose_at("B", 0.0)


def test_width_and_height_interpolate_along_the_lane() -> None:
    lane_map = _map(_lane())
    x, y, z, heading = lane_map.pose_at("A", 8.0)
    assert (x, y, z) == pytest.approx((3.0, 7.0, 0.5))
    assert heading == pytest.approx(math.pi / 2)
    p = lane_map.project(x, y)
    assert p.width == pytest.approx(3.5 + 0.5 * 0.5)
    assert p.s == pytest.approx(8.0)


def test_bounds_pad_centreline_points_by_half_their_width() -> None:
    assert _map(_lane()).bounds() == pytest.approx((-1.5, -1.5, 5.0, 12.0))
