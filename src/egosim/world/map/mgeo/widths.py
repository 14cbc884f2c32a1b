"""Lane widths of MGeo links: from their lane boundaries, else from their width fields."""

from __future__ import annotations

import numpy as np

from egosim.world.arrays import FloatArray
from egosim.world.map.mgeo.records import Record

DEFAULT_LANE_WIDTH_M = 3.5


def distance_to_polyline(points: FloatArray, polyline: FloatArray) -> FloatArray:
    """Planar distance from each of (N, 2+) points to an (M >= 1, 2+) polyline."""
    p = points[:, None, :2]
    distance: FloatArray
    if len(polyline) == 1:
        distance = np.hypot(*(points[:, :2] - polyline[0, :2]).T)
        return distance
    a = polyline[None, :-1, :2]
    ab = polyline[None, 1:, :2] - a
    length_sq = np.maximum(np.sum(ab * ab, axis=2), 1e-18)
    t = np.clip(np.sum((p - a) * ab, axis=2) / length_sq, 0.0, 1.0)
    gap = p - (a + t[..., None] * ab)
    distance = np.sqrt(np.sum(gap * gap, axis=2)).min(axis=1)
    return distance


def link_widths(
    link: Record, centerline: FloatArray, stations: FloatArray, boundaries: dict[str, FloatArray]
) -> FloatArray:
    """Width at each centreline point.

    A link naming boundaries on both sides (`lane_mark_left` / `lane_mark_right`, present in
    lane_boundary_set.json) is as wide as the gap between them, unless its width is forced
    (`force_width_start`); otherwise `width_start` runs linearly to `width_end` (3.5 m when
    absent).
    """
    left = [boundaries[i] for i in link.ids("lane_mark_left") if i in boundaries]
    right = [boundaries[i] for i in link.ids("lane_mark_right") if i in boundaries]
    if left and right and not link.flag("force_width_start"):
        return _nearest(centerline, left) + _nearest(centerline, right)
    start = link.number("width_start") or DEFAULT_LANE_WIDTH_M
    end = link.number("width_end") or start
    if start <= 0.0 or end <= 0.0:
        raise link.fail(f"width_start / width_end must be positive, got {start}, {end}")
    widths: FloatArray = start + (end - start) * stations / stations[-1]
    return widths


def _nearest(points: FloatArray, polylines: list[FloatArray]) -> FloatArray:
    nearest: FloatArray = np.minimum.reduce(
        [distance_to_polyline(points, line) for line in polylines]
    )
    return nearest
