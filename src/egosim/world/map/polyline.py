"""Plane-curve helpers for building lane centrelines (pure numpy)."""

from __future__ import annotations

import math

import numpy as np

from egosim.world.arrays import FloatArray, IntArray


def stations(points: FloatArray) -> FloatArray:
    """Cumulative planar arclength at each vertex of an (N, 2+) polyline."""
    steps = np.hypot(*np.diff(points[:, :2], axis=0).T)
    return np.concatenate(([0.0], np.cumsum(steps)))


def segment_headings(points: FloatArray) -> FloatArray:
    """Heading (rad, CCW from +x) of each of the N-1 segments."""
    delta = np.diff(points[:, :2], axis=0)
    return np.arctan2(delta[:, 1], delta[:, 0])


def offset_left(points: FloatArray, distance: float) -> FloatArray:
    """Parallel curve `distance` metres to the left (negative: right) of an (N, 2) polyline.

    Interior vertices move along the bisector by distance / cos(half turn) so every
    segment stays exactly `distance` from its parent; end vertices move square to their
    segment, so lines meant to join end to end should end on straight pieces.
    """
    delta = np.diff(points, axis=0)
    normals = np.column_stack((-delta[:, 1], delta[:, 0])) / np.hypot(*delta.T)[:, None]
    vertex_normals = np.empty_like(points)
    vertex_normals[0] = normals[0]
    vertex_normals[-1] = normals[-1]
    bisector = normals[:-1] + normals[1:]
    bisector /= np.hypot(*bisector.T)[:, None]
    cos_half = np.sum(bisector * normals[1:], axis=1)
    vertex_normals[1:-1] = bisector / cos_half[:, None]
    return points + distance * vertex_normals


def kept_vertices(polylines: tuple[FloatArray, ...], tolerance: float) -> IntArray:
    """Indices of the vertices that keep every one of these equally long polylines
    within `tolerance` of itself (Douglas-Peucker on the worst of them), so polylines
    that share their vertices (a strip's two edges) stay paired. Ends are always kept."""
    stacked = np.stack(polylines)
    count = stacked.shape[1]
    if count <= 2:
        return np.arange(count)
    kept = np.zeros(count, dtype=bool)
    kept[[0, -1]] = True
    spans = [(0, count - 1)]
    while spans:
        first, last = spans.pop()
        if last - first < 2:
            continue
        a, b = stacked[:, first : first + 1], stacked[:, last : last + 1]
        along, offsets = b - a, stacked[:, first + 1 : last] - a
        # ndarray methods, not np.sum: this loop runs thousands of times per scene.
        length2 = (along * along).sum(axis=2, keepdims=True).clip(1e-18, None)
        t = ((offsets * along).sum(axis=2, keepdims=True) / length2).clip(0.0, 1.0)
        apart = offsets - t * along
        worst = (apart * apart).sum(axis=2).max(axis=0)
        farthest = int(worst.argmax())
        if worst[farthest] > tolerance * tolerance:
            split = first + 1 + farthest
            kept[split] = True
            spans += [(first, split), (split, last)]
    return np.flatnonzero(kept)


def between(points: FloatArray, start: float, end: float) -> FloatArray:
    """The part of an (N, 2) polyline between stations `start` < `end`."""
    s = stations(points)
    inner = points[(s > start) & (s < end)]
    ends = np.column_stack([np.interp([start, end], s, points[:, k]) for k in range(2)])
    return np.vstack((ends[:1], inner, ends[1:]))


def trim(points: FloatArray, start: float, end: float) -> FloatArray:
    """The (N, 2) polyline without its first `start` and last `end` metres."""
    return between(points, start, float(stations(points)[-1]) - end)


def arc(
    center: tuple[float, float], radius: float, start: float, sweep: float, step: float = 2.0
) -> FloatArray:
    """Points on a circular arc from angle `start` over `sweep` rad (CCW positive)."""
    count = max(2, math.ceil(abs(sweep) * radius / step) + 1)
    angles = start + np.linspace(0.0, sweep, count)
    return np.column_stack(
        (center[0] + radius * np.cos(angles), center[1] + radius * np.sin(angles))
    )


def connector_curve(
    start: FloatArray, start_heading: float, end: FloatArray, end_heading: float, step: float = 1.0
) -> FloatArray:
    """Cubic Bézier leaving `start` along `start_heading` and reaching `end` along `end_heading`.

    The handle length (2/3 tan(θ/4) / sin(θ/2) of the chord) makes a symmetric turn of
    angle θ a near-exact circular arc and θ -> 0 a straight line.
    """
    chord = float(np.hypot(*(end - start)))
    turn = abs(math.remainder(end_heading - start_heading, math.tau))
    if turn < 1e-9:
        handle = chord / 3.0
    else:
        handle = chord * (2.0 / 3.0) * math.tan(turn / 4.0) / math.sin(turn / 2.0)
    p0 = start
    p1 = start + handle * np.array([math.cos(start_heading), math.sin(start_heading)])
    p2 = end - handle * np.array([math.cos(end_heading), math.sin(end_heading)])
    p3 = end
    count = max(4, math.ceil(chord * (1.0 + turn / 2.0) / step) + 1)
    t = np.linspace(0.0, 1.0, count)[:, None]
    u = 1.0 - t
    return u**3 * p0 + 3 * u**2 * t * p1 + 3 * u * t**2 * p2 + t**3 * p3
