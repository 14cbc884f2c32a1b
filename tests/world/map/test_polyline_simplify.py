"""kept_vertices: Douglas-Peucker over polylines that share their vertices."""

from __future__ import annotations

import numpy as np

from egosim.world.map.polyline import kept_vertices


def distances_to_polyline(points: np.ndarray, polyline: np.ndarray) -> np.ndarray:
    """Each point's distance to the nearest segment of `polyline`."""
    a, b = polyline[:-1][None], polyline[1:][None]
    along = b - a
    t = np.clip(
        np.sum((points[:, None] - a) * along, axis=2) / np.sum(along * along, axis=2), 0.0, 1.0
    )
    nearest = a + t[..., None] * along
    return np.min(np.linalg.norm(points[:, None] - nearest, axis=2), axis=1)


def test_a_straight_densely_sampled_strip_keeps_its_two_ends() -> None:
    x = np.linspace(0.0, 60.0, 31)
    left = np.column_stack((x, np.full_like(x, 1.75), np.zeros_like(x)))
    right = np.column_stack((x, np.full_like(x, -1.75), np.zeros_like(x)))
    assert kept_vertices((left, right), 0.005).tolist() == [0, 30]


def test_an_arc_keeps_every_vertex_within_the_tolerance_of_its_simplified_self() -> None:
    # A right turn: radius 8 m, sampled every 2 m; the chord of two such steps sags
    # by about 25 cm, so at 5 mm every vertex stays and at 0.3 m some go.
    angles = np.linspace(0.0, np.pi / 2, 8)
    inner = np.column_stack((8.0 * np.cos(angles), 8.0 * np.sin(angles), np.zeros(8)))
    outer = inner * np.array([11.5 / 8.0, 11.5 / 8.0, 1.0])
    assert len(kept_vertices((inner, outer), 0.005)) == 8
    for tolerance in (0.05, 0.3, 1.0):
        kept = kept_vertices((inner, outer), tolerance)
        assert kept[0] == 0 and kept[-1] == 7
        for polyline in (inner, outer):
            assert np.max(distances_to_polyline(polyline, polyline[kept])) <= tolerance


def test_a_vertex_kept_for_one_edge_is_kept_for_both() -> None:
    # The right edge is straight; the left bulges at x = 10 (a widening lane).
    x = np.linspace(0.0, 20.0, 11)
    left = np.column_stack((x, 1.75 + 0.5 * (x == 10.0), np.zeros_like(x)))
    right = np.column_stack((x, np.full_like(x, -1.75), np.zeros_like(x)))
    assert kept_vertices((left, right), 0.01).tolist() == [0, 4, 5, 6, 10]


def test_elevation_counts_as_a_deviation() -> None:
    x = np.linspace(0.0, 20.0, 5)
    crest = np.column_stack((x, np.zeros_like(x), [0.0, 0.0, 0.2, 0.0, 0.0]))
    assert kept_vertices((crest,), 0.01).tolist() == [0, 1, 2, 3, 4]
    assert kept_vertices((crest,), 0.3).tolist() == [0, 4]
