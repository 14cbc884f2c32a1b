"""The swept collision test (world/collision.py's touching_pairs) as compiled loops: the
broad phase's sweep along x, then the separating-axis test at sub-steps of the motion."""

from __future__ import annotations

import math

import numpy as np

from egosim.world.arrays import FloatArray, IntArray
from egosim.world.kernels import kernel
from egosim.world.kernels.numpy_scalars import maximum, minimum, remainder
from egosim.world.kernels.sorting import goes_before, lexsort_argsort, resort


@kernel
def _half_extent(heading: float, length: float, width: float) -> tuple[float, float]:
    """Half the size of a rectangle's axis-aligned bounding box (Footprints.half_extents)."""
    c, s = abs(math.cos(heading)), abs(math.sin(heading))
    half_l, half_w = length / 2.0, width / 2.0
    return c * half_l + s * half_w, s * half_l + c * half_w


@kernel
def _half_extents(headings: FloatArray, lengths: FloatArray, widths: FloatArray) -> FloatArray:
    """(N, 2) half extents of each rectangle."""
    n = headings.shape[0]
    extents = np.empty((n, 2))
    for k in range(n):
        extents[k, 0], extents[k, 1] = _half_extent(headings[k], lengths[k], widths[k])
    return extents


@kernel
def _corners(x: float, y: float, heading: float, length: float, width: float) -> FloatArray:
    """collision.corners of one rectangle: (4, 2), counter-clockwise."""
    c, s = math.cos(heading), math.sin(heading)
    along_x, along_y = c * (length / 2.0), s * (length / 2.0)
    across_x, across_y = -s * (width / 2.0), c * (width / 2.0)
    corners = np.empty((4, 2))
    corners[0, 0], corners[0, 1] = x + along_x + across_x, y + along_y + across_y
    corners[1, 0], corners[1, 1] = x - along_x + across_x, y - along_y + across_y
    corners[2, 0], corners[2, 1] = x - along_x - across_x, y - along_y - across_y
    corners[3, 0], corners[3, 1] = x + along_x - across_x, y + along_y - across_y
    return corners


@kernel
def _separated_along(axis_heading: float, corners_a: FloatArray, corners_b: FloatArray) -> bool:
    ax, ay = math.cos(axis_heading), math.sin(axis_heading)
    low_a, high_a, low_b, high_b = np.inf, -np.inf, np.inf, -np.inf
    for k in range(4):
        pa = corners_a[k, 0] * ax + corners_a[k, 1] * ay
        pb = corners_b[k, 0] * ax + corners_b[k, 1] * ay
        # np.minimum and np.maximum, as the numpy path's min() and max() reduce: a NaN
        # corner (odd input) makes the bounds NaN, and NaN bounds separate nothing.
        low_a, high_a = minimum(low_a, pa), maximum(high_a, pa)
        low_b, high_b = minimum(low_b, pb), maximum(high_b, pb)
    return high_a < low_b or high_b < low_a


@kernel
def overlap(
    a: tuple[float, float, float, float, float], b: tuple[float, float, float, float, float]
) -> bool:
    """collision._overlap of two rectangles (x, y, heading, length, width)."""
    corners_a = _corners(a[0], a[1], a[2], a[3], a[4])
    corners_b = _corners(b[0], b[1], b[2], b[3], b[4])
    for axis_heading in (a[2], a[2] + math.pi / 2, b[2], b[2] + math.pi / 2):
        if _separated_along(axis_heading, corners_a, corners_b):
            return False
    return True


@kernel
def _substeps(travel_in_substeps: float, max_substeps: int) -> int:
    """collision.touching_pairs's sub-step count: ceil(travel), within 1..max_substeps;
    1 where the travel is not a number (a cast of NaN or inf to an integer is undefined)."""
    if not travel_in_substeps > 1.0:
        return 1
    if travel_in_substeps >= max_substeps:
        return max_substeps
    return math.ceil(travel_in_substeps)


@kernel
def _between(
    k: int,
    fraction: float,
    before_centres: FloatArray,
    before_headings: FloatArray,
    after_centres: FloatArray,
    after_headings: FloatArray,
    after_lengths: FloatArray,
    after_widths: FloatArray,
) -> tuple[float, float, float, float, float]:
    """Box k at `fraction` of its motion (collision._interpolate): x, y, heading, length,
    width."""
    turn = remainder(after_headings[k] - before_headings[k] + math.pi, math.tau) - math.pi
    return (
        before_centres[k, 0] + fraction * (after_centres[k, 0] - before_centres[k, 0]),
        before_centres[k, 1] + fraction * (after_centres[k, 1] - before_centres[k, 1]),
        before_headings[k] + fraction * turn,
        after_lengths[k],
        after_widths[k],
    )


@kernel
def touching_pairs(
    before_centres: FloatArray,
    before_headings: FloatArray,
    before_lengths: FloatArray,
    before_widths: FloatArray,
    after_centres: FloatArray,
    after_headings: FloatArray,
    after_lengths: FloatArray,
    after_widths: FloatArray,
    max_substep_m: float,
    max_substeps: int,
    before_extents: FloatArray,
    earlier_order: IntArray,
) -> tuple[IntArray, FloatArray, IntArray]:
    """collision.touching_pairs: (K, 2) pairs i < j, sorted, that touch during the motion;
    then the half extents of the boxes' bounds after it (the next sweep's before_extents)
    and the boxes' order along x (the next sweep's earlier_order).

    before_extents: the before boxes' half extents as an earlier sweep returned them, or
    none (no rows): worked out; a box whose heading and size did not change keeps them.
    earlier_order: a permutation of the boxes close to their order along x now, or none:
    sorted from scratch. Neither changes the pairs."""
    n = before_headings.shape[0]
    if before_extents.shape[0] == n:
        e0 = before_extents
    else:
        e0 = _half_extents(before_headings, before_lengths, before_widths)
    e1 = np.empty((n, 2))
    low = np.empty((n, 2))
    high = np.empty((n, 2))
    low_x = np.empty(n)
    for k in range(n):
        if (
            after_headings[k] == before_headings[k]
            and after_lengths[k] == before_lengths[k]
            and after_widths[k] == before_widths[k]
        ):
            e1[k, 0], e1[k, 1] = e0[k, 0], e0[k, 1]
        else:
            e1[k, 0], e1[k, 1] = _half_extent(after_headings[k], after_lengths[k], after_widths[k])
        for d in range(2):
            low[k, d] = minimum(before_centres[k, d] - e0[k, d], after_centres[k, d] - e1[k, d])
            high[k, d] = maximum(before_centres[k, d] + e0[k, d], after_centres[k, d] + e1[k, d])
        low_x[k] = low[k, 0]
    order = resort(low_x, earlier_order)
    sorted_low = low_x[order]
    keys = np.empty(16, dtype=np.int64)
    found = 0
    for a in range(n):
        i = order[a]
        for b in range(a + 1, n):
            # Only the boxes starting before box i ends (searchsorted's right side, walked
            # rather than searched: most boxes reach few others).
            if not goes_before(sorted_low[b], high[i, 0], True):
                break
            j = order[b]
            if not (low[i, 1] <= high[j, 1] and low[j, 1] <= high[i, 1]):
                continue
            first, second = min(i, j), max(i, j)
            travel_x = (after_centres[first, 0] - before_centres[first, 0]) - (
                after_centres[second, 0] - before_centres[second, 0]
            )
            travel_y = (after_centres[first, 1] - before_centres[first, 1]) - (
                after_centres[second, 1] - before_centres[second, 1]
            )
            steps = _substeps(math.hypot(travel_x, travel_y) / max_substep_m, max_substeps)
            for step in range(1, steps + 1):
                fraction = step / steps
                box_first = _between(
                    first, fraction, before_centres, before_headings, after_centres,
                    after_headings, after_lengths, after_widths,
                )  # fmt: skip
                box_second = _between(
                    second, fraction, before_centres, before_headings, after_centres,
                    after_headings, after_lengths, after_widths,
                )  # fmt: skip
                if overlap(box_first, box_second):
                    if found == keys.shape[0]:
                        keys = np.concatenate((keys, np.empty(found, dtype=np.int64)))
                    keys[found] = first * n + second
                    found += 1
                    break
    keys = keys[:found]
    result = np.empty((found, 2), dtype=np.int64)
    for row, k in enumerate(lexsort_argsort(keys, np.zeros(found))):
        result[row, 0], result[row, 1] = keys[k] // n, keys[k] % n
    return result, e1, order
