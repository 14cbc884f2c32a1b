"""Lane projection (map/projection.py's SegmentTable.project) as one compiled loop."""

from __future__ import annotations

import math

import numpy as np

from egosim.world.arrays import FloatArray, IntArray
from egosim.world.kernels import kernel
from egosim.world.kernels.numpy_scalars import clip, fmax, remainder

PRUNE_MARGIN = 1e-9
"""Relative margin of the squared-distance test that skips a segment: far larger than
the rounding of either side, so a skipped segment could never have won or tied."""


@kernel
def _pair_cost(
    x: float,
    y: float,
    hint: float,
    g: int,
    start: FloatArray,
    delta: FloatArray,
    length_sq: FloatArray,
    heading: FloatArray,
    heading_weight: float,
    wrong_way_penalty: float,
    bound: float,
) -> tuple[float, float]:
    """(cost, t) of point (x, y) with heading hint (NaN: none) against segment g; cost
    inf when the distance alone already exceeds `bound` (the heading terms only add)."""
    rel_x = x - start[g, 0]
    rel_y = y - start[g, 1]
    along = (rel_x * delta[g, 0] + rel_y * delta[g, 1]) / length_sq[g]
    t = clip(along, 0.0, 1.0)
    gap_x, gap_y = rel_x - t * delta[g, 0], rel_y - t * delta[g, 1]
    if gap_x * gap_x + gap_y * gap_y > bound * bound * (1.0 + PRUNE_MARGIN):
        return math.inf, t
    cost = math.hypot(gap_x, gap_y)
    error = abs(remainder(heading[g] - hint + math.pi, math.tau) - math.pi)
    penalty = wrong_way_penalty if error > math.pi / 2 else 0.0
    return cost + (fmax(heading_weight * error, 0.0) + penalty), t


@kernel
def best_segments(
    xy: FloatArray,
    hints: FloatArray,
    start: FloatArray,
    delta: FloatArray,
    length_sq: FloatArray,
    heading: FloatArray,
    origin: FloatArray,
    cell_size: float,
    shape: IntArray,
    cell_segments: IntArray,
    cell_offsets: IntArray,
    heading_weight: float,
    wrong_way_penalty: float,
) -> tuple[IntArray, FloatArray]:
    """Each point's best segment and its parameter t along it: the least cost within the
    grid cells of a ring that doubles until nothing outside can be nearer, else over every
    segment; ties go to the lower segment index."""
    n = xy.shape[0]
    best_seg = np.zeros(n, dtype=np.int64)
    best_t = np.zeros(n)
    max_ring = max(shape[0], shape[1])
    for p in range(n):
        x, y, hint = xy[p, 0], xy[p, 1], hints[p]
        ix = math.floor((x - origin[0]) / cell_size)
        iy = math.floor((y - origin[1]) / cell_size)
        done = False
        ring = 1
        while not done and ring <= max_ring:
            found_seg, found_t, found_cost = -1, 0.0, math.inf
            for cx in range(max(ix - ring, 0), min(ix + ring + 1, shape[0])):
                for cy in range(max(iy - ring, 0), min(iy + ring + 1, shape[1])):
                    key = cx * shape[1] + cy
                    for k in range(cell_offsets[key], cell_offsets[key + 1]):
                        g = cell_segments[k]
                        cost, t = _pair_cost(
                            x, y, hint, g, start, delta, length_sq, heading,
                            heading_weight, wrong_way_penalty, found_cost,
                        )  # fmt: skip
                        if cost < found_cost or (cost == found_cost and g < found_seg):
                            found_seg, found_t, found_cost = g, t, cost
            if found_seg >= 0 and found_cost <= ring * cell_size:
                best_seg[p], best_t[p] = found_seg, found_t
                done = True
            ring *= 2
        if not done:
            found_seg, found_t, found_cost = 0, 0.0, math.inf
            for g in range(start.shape[0]):
                cost, t = _pair_cost(
                    x, y, hint, g, start, delta, length_sq, heading,
                    heading_weight, wrong_way_penalty, found_cost,
                )  # fmt: skip
                if cost < found_cost:
                    found_seg, found_t, found_cost = g, t, cost
            best_seg[p], best_t[p] = found_seg, found_t
    return best_seg, best_t


@kernel
def project_points(
    xy: FloatArray,
    hints: FloatArray,
    start: FloatArray,
    delta: FloatArray,
    length_sq: FloatArray,
    length: FloatArray,
    heading: FloatArray,
    s0: FloatArray,
    width0: FloatArray,
    width1: FloatArray,
    segment_lane: IntArray,
    origin: FloatArray,
    cell_size: float,
    shape: IntArray,
    cell_segments: IntArray,
    cell_offsets: IntArray,
    heading_weight: float,
    wrong_way_penalty: float,
) -> tuple[IntArray, FloatArray]:
    """Each point's best lane (SegmentTable.project): its lane index, and (6, N) station,
    lateral offset (left positive), heading, distances to the left and right boundaries,
    and width. (Few arguments and results of few kinds: a call's overhead is per item.)"""
    seg, t = best_segments(
        xy, hints, start, delta, length_sq, heading, origin, cell_size, shape,
        cell_segments, cell_offsets, heading_weight, wrong_way_penalty,
    )  # fmt: skip
    n = xy.shape[0]
    lane = np.empty(n, dtype=np.int64)
    facts = np.empty((6, n))
    s, lateral, direction, left, right, width = (
        facts[0], facts[1], facts[2], facts[3], facts[4], facts[5],
    )  # fmt: skip
    for p in range(n):
        g, tp = seg[p], t[p]
        rel_x = xy[p, 0] - start[g, 0]
        rel_y = xy[p, 1] - start[g, 1]
        distance = math.hypot(rel_x - tp * delta[g, 0], rel_y - tp * delta[g, 1])
        cross = delta[g, 0] * rel_y - delta[g, 1] * rel_x
        offset = distance if cross >= 0.0 else -distance
        w = width0[g] + tp * (width1[g] - width0[g])
        lane[p] = segment_lane[g]
        s[p] = s0[g] + tp * length[g]
        lateral[p] = offset
        direction[p] = heading[g]
        left[p] = w / 2.0 - offset
        right[p] = w / 2.0 + offset
        width[p] = w
    return lane, facts
