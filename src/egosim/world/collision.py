"""Oriented-box collisions between placed objects, and the records they leave.

Footprints are rectangles in the plane (heights always overlap on the ground). A broad
phase sweeps the axis-aligned bounds of each box's motion over the step along x; the
narrow phase runs the separating-axis test on the candidate pairs at sub-steps of the
motion, never more than `max_substep_m` of relative travel apart, so no pair tunnels
through each other whatever the speeds and the step.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from egosim.world import kernels
from egosim.world.arrays import FloatArray, IntArray
from egosim.world.kernels import collision as compiled
from egosim.world.traffic.objects import ObjectState, ObjectTable

DEFAULT_MAX_SUBSTEP_M = 0.1
"""Largest relative travel of two boxes between two overlap tests, m."""
MAX_SUBSTEPS = 64


@dataclass(frozen=True, eq=False)
class Footprints:
    """N rectangles: centres (N, 2) m, headings (N,) rad, lengths and widths (N,) m."""

    centres: FloatArray
    headings: FloatArray
    lengths: FloatArray
    widths: FloatArray

    def half_extents(self) -> FloatArray:
        """(N, 2) half size of each rectangle's axis-aligned bounding box, m."""
        c, s = np.abs(np.cos(self.headings)), np.abs(np.sin(self.headings))
        half_l, half_w = self.lengths / 2.0, self.widths / 2.0
        return np.column_stack((c * half_l + s * half_w, s * half_l + c * half_w))

    @classmethod
    def of(cls, table: ObjectTable) -> Footprints:
        """The footprints of a table's rows (views of its columns)."""
        if len(table.headings) == 0:
            return _NO_FOOTPRINTS
        return cls(table.positions[:, :2], table.headings, table.sizes[:, 0], table.sizes[:, 1])


_NO_FOOTPRINTS = Footprints(np.empty((0, 2)), np.empty(0), np.empty(0), np.empty(0))
_NO_EXTENTS = np.empty((0, 2))
_NO_ORDER = np.empty(0, np.int64)


class SweptPairs:
    """touching_pairs step after step, where each sweep's `before` is the last one's
    `after`: the compiled sweep then starts from the boxes' extents and their order
    along x as it found them last time (boxes barely move or turn in a step) instead of
    working them out again. The pairs are the same either way."""

    def __init__(self) -> None:
        self._last: tuple[Footprints | None, FloatArray, IntArray] = (None, _NO_EXTENTS, _NO_ORDER)

    def pairs(
        self, before: Footprints, after: Footprints, max_substep_m: float = DEFAULT_MAX_SUBSTEP_M
    ) -> IntArray:
        """touching_pairs(before, after, max_substep_m)."""
        if not kernels.ACTIVE:
            return touching_pairs(before, after, max_substep_m)
        last, extents, order = self._last
        pairs, after_extents, after_order = _compiled_pairs(
            before, after, max_substep_m, extents if last is before else _NO_EXTENTS, order
        )
        self._last = (after, after_extents, after_order)
        return pairs


def _compiled_pairs(
    before: Footprints,
    after: Footprints,
    max_substep_m: float,
    before_extents: FloatArray,
    earlier_order: IntArray,
) -> tuple[IntArray, FloatArray, IntArray]:
    """The compiled sweep: the pairs, then the after boxes' half extents and their order
    along x (kernels/collision.py's touching_pairs)."""
    result: tuple[IntArray, FloatArray, IntArray] = compiled.touching_pairs(
        before.centres,
        before.headings,
        before.lengths,
        before.widths,
        after.centres,
        after.headings,
        after.lengths,
        after.widths,
        max_substep_m,
        MAX_SUBSTEPS,
        before_extents,
        earlier_order,
    )
    return result


def touching_pairs(
    before: Footprints, after: Footprints, max_substep_m: float = DEFAULT_MAX_SUBSTEP_M
) -> IntArray:
    """(K, 2) index pairs i < j whose rectangles overlap at some point of the motion from
    `before` to `after` (positions in between are interpolated), sorted."""
    if kernels.ACTIVE:
        return _compiled_pairs(before, after, max_substep_m, _NO_EXTENTS, _NO_ORDER)[0]
    extents_before, extents_after = before.half_extents(), after.half_extents()
    low = np.minimum(before.centres - extents_before, after.centres - extents_after)
    high = np.maximum(before.centres + extents_before, after.centres + extents_after)
    i, j = _sweep(low, high)
    if i.size == 0:
        return np.empty((0, 2), np.int64)
    travel = (after.centres - before.centres)[i] - (after.centres - before.centres)[j]
    # fmax/fmin, not clip: a travel that is not a number (odd input: boxes at infinity)
    # takes one sub-step rather than an undefined count.
    substeps = np.fmin(
        np.fmax(np.ceil(np.hypot(travel[:, 0], travel[:, 1]) / max_substep_m), 1.0),
        MAX_SUBSTEPS,
    ).astype(np.int64)
    pair = np.repeat(np.arange(i.size), substeps)
    first = np.cumsum(substeps) - substeps
    fraction = (np.arange(pair.size) - first[pair] + 1) / substeps[pair]
    hit = _overlap(
        _interpolate(before, after, i[pair], fraction),
        _interpolate(before, after, j[pair], fraction),
    )
    touching = np.unique(pair[hit])
    result = np.column_stack((i[touching], j[touching]))
    return result[np.lexsort((result[:, 1], result[:, 0]))]


def _sweep(low: FloatArray, high: FloatArray) -> tuple[IntArray, IntArray]:
    """Pairs (i < j) whose bounds overlap: sort by x, pair each box with those starting
    before it ends, keep those overlapping in y too."""
    order = np.argsort(low[:, 0], kind="stable")
    sorted_low = low[order, 0]
    reach = np.searchsorted(sorted_low, high[order, 0], side="right")
    count = np.maximum(reach - np.arange(len(order)) - 1, 0)
    a = np.repeat(np.arange(len(order)), count)
    first = np.cumsum(count) - count
    b = np.arange(a.size) - first[a] + a + 1
    i, j = order[a], order[b]
    overlap_y = (low[i, 1] <= high[j, 1]) & (low[j, 1] <= high[i, 1])
    i, j = i[overlap_y], j[overlap_y]
    return np.minimum(i, j), np.maximum(i, j)


def _interpolate(
    before: Footprints, after: Footprints, index: IntArray, fraction: FloatArray
) -> Footprints:
    turn = np.remainder(after.headings[index] - before.headings[index] + math.pi, math.tau)
    turn -= math.pi
    return Footprints(
        centres=before.centres[index]
        + fraction[:, None] * (after.centres[index] - before.centres[index]),
        headings=before.headings[index] + fraction * turn,
        lengths=after.lengths[index],
        widths=after.widths[index],
    )


def corners(boxes: Footprints) -> FloatArray:
    """(N, 4, 2) corners, counter-clockwise."""
    c, s = np.cos(boxes.headings), np.sin(boxes.headings)
    along = np.stack((c, s), axis=1) * (boxes.lengths / 2.0)[:, None]
    across = np.stack((-s, c), axis=1) * (boxes.widths / 2.0)[:, None]
    centre = boxes.centres
    return np.stack(
        (
            centre + along + across,
            centre - along + across,
            centre - along - across,
            centre + along - across,
        ),
        axis=1,
    )


def _overlap(a: Footprints, b: Footprints) -> npt.NDArray[np.bool_]:
    """Separating-axis test on the four edge normals of two rectangles, pairwise."""
    corners_a, corners_b = corners(a), corners(b)
    separated = np.zeros(len(a.headings), dtype=bool)
    for heading in (a.headings, a.headings + math.pi / 2, b.headings, b.headings + math.pi / 2):
        axis = np.stack((np.cos(heading), np.sin(heading)), axis=1)[:, None, :]
        projection_a = np.sum(corners_a * axis, axis=2)
        projection_b = np.sum(corners_b * axis, axis=2)
        separated |= (projection_a.max(axis=1) < projection_b.min(axis=1)) | (
            projection_b.max(axis=1) < projection_a.min(axis=1)
        )
    return ~separated


REJOIN_S = 1.0
"""A pair touching again within this long (s) of parting goes on with the same collision:
a crash that bounces, or a car pushing a cone it keeps catching up with, is one."""


class ContactTracker:
    """Remembers which pairs (by unique id) touch, since when and when they last did, so a
    collision is recorded once, when it begins, and a lasting contact is known as one."""

    def __init__(self) -> None:
        self.began_at: dict[tuple[int, int], float] = {}
        """Each pair touching at the last call: the time (s) its collision began."""
        self._touch: dict[tuple[int, int], tuple[float, float]] = {}
        """Pairs that touched within REJOIN_S: (collision began, last touched), s."""

    def begin(self, pairs: list[tuple[int, int]], now: float = 0.0) -> list[tuple[int, int]]:
        """The pairs of `pairs` (touching at time `now`, s) whose collision begins now: not
        touching at the last call, nor within REJOIN_S before."""
        fresh = []
        for pair in pairs:
            known = self._touch.get(pair)
            if known is None or now - known[1] > REJOIN_S:
                fresh.append(pair)
                known = (now, now)
            self._touch[pair] = (known[0], now)
        self._touch = {p: t for p, t in self._touch.items() if now - t[1] <= REJOIN_S}
        self.began_at = {pair: self._touch[pair][0] for pair in pairs}
        return fresh

    def clear(self) -> None:
        self.began_at.clear()
        self._touch.clear()


@dataclass(frozen=True)
class EgoCollision:
    """CollisionData semantics: an ego touched a placed object at time_s (s)."""

    time_s: float
    ego_id: int
    other: ObjectState
    """The collided object as it was at impact; other.position is its global position."""


@dataclass(frozen=True)
class VehicleCollision:
    """VehicleCollision semantics: two NPC vehicles touched at time_s (s)."""

    time_s: float
    vehicles: tuple[ObjectState, ObjectState]
