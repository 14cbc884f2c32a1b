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
    if hint != hint:  # noqa: PLR0124
        # No hint: the heading error is NaN, and its terms add 0 (fmax, and no penalty).
        return cost + 0.0, t
    error = abs(remainder(heading[g] - hint + math.pi, math.tau) - math.pi)
    penalty = wrong_way_penalty if error > math.pi / 2 else 0.0
    return cost + (fmax(heading_weight * error, 0.0) + penalty), t


@kernel
def _best_segment(
    x: float,
    y: float,
    hint: float,
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
) -> tuple[int, float]:
    """A point's best segment and its parameter t along it: the least cost within the
    grid cells of a ring that doubles until nothing outside can be nearer, else over every
    segment; ties go to the lower segment index."""
    max_ring = max(shape[0], shape[1])
    ix = math.floor((x - origin[0]) / cell_size)
    iy = math.floor((y - origin[1]) / cell_size)
    ring = 1
    while ring <= max_ring:
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
            return found_seg, found_t
        ring *= 2
    found_seg, found_t, found_cost = 0, 0.0, math.inf
    for g in range(start.shape[0]):
        cost, t = _pair_cost(
            x, y, hint, g, start, delta, length_sq, heading,
            heading_weight, wrong_way_penalty, found_cost,
        )  # fmt: skip
        if cost < found_cost:
            found_seg, found_t, found_cost = g, t, cost
    return found_seg, found_t


@kernel
def _same_bits(a: float, b: float) -> bool:
    """a and b are the same number, zeros of the same sign, or both not a number (a
    projection does the same with any NaN hint)."""
    if a != a:  # noqa: PLR0124
        return b != b  # noqa: PLR0124
    return a == b and math.copysign(1.0, a) == math.copysign(1.0, b)


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
    coordinate_limit: float,
    memory_points: FloatArray,
    memory_lanes: IntArray,
    memory_facts: FloatArray,
    memory_count: IntArray,
) -> tuple[IntArray, FloatArray]:
    """Each point's best lane (SegmentTable.project): its lane index, and (6, N) station,
    lateral offset (left positive), heading, distances to the left and right boundaries,
    and width. (Few arguments and results of few kinds: a call's overhead is per item.)

    Nothing (no rows) where a coordinate is not within coordinate_limit of 0 (not a
    number, or no place on Earth): its grid cell would overflow the loop's integers.

    The memory holds the points of the last call (rows x, y, hint, the first
    memory_count[0] of them) and their results: a point at the same place in the list,
    with the same bits, is copied from there instead of searched for again (the agents
    of a step are listed in the same order every step, and many stand still). It is
    updated in place when it has room for every point.
    """
    n = xy.shape[0]
    for p in range(n):
        if not (abs(xy[p, 0]) < coordinate_limit and abs(xy[p, 1]) < coordinate_limit):
            return np.empty(0, dtype=np.int64), np.empty((6, 0))
    known = memory_count[0]
    remember = n <= memory_points.shape[0]
    lane = np.empty(n, dtype=np.int64)
    facts = np.empty((6, n))
    for p in range(n):
        x, y, hint = xy[p, 0], xy[p, 1], hints[p]
        if (
            p < known
            and _same_bits(x, memory_points[p, 0])
            and _same_bits(y, memory_points[p, 1])
            and _same_bits(hint, memory_points[p, 2])
        ):
            lane[p] = memory_lanes[p]
            for row in range(6):
                facts[row, p] = memory_facts[row, p]
            continue
        g, tp = _best_segment(
            x, y, hint, start, delta, length_sq, heading, origin, cell_size, shape,
            cell_segments, cell_offsets, heading_weight, wrong_way_penalty,
        )  # fmt: skip
        rel_x = x - start[g, 0]
        rel_y = y - start[g, 1]
        distance = math.hypot(rel_x - tp * delta[g, 0], rel_y - tp * delta[g, 1])
        cross = delta[g, 0] * rel_y - delta[g, 1] * rel_x
        offset = distance if cross >= 0.0 else -distance
        w = width0[g] + tp * (width1[g] - width0[g])
        lane[p] = segment_lane[g]
        facts[0, p] = s0[g] + tp * length[g]
        facts[1, p] = offset
        facts[2, p] = heading[g]
        facts[3, p] = w / 2.0 - offset
        facts[4, p] = w / 2.0 + offset
        facts[5, p] = w
        if remember:
            memory_points[p, 0], memory_points[p, 1], memory_points[p, 2] = x, y, hint
            memory_lanes[p] = lane[p]
            for row in range(6):
                memory_facts[row, p] = facts[row, p]
    memory_count[0] = n if remember else 0
    return lane, facts
