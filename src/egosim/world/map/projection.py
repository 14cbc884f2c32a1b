"""Vectorised projection of points onto lane centrelines."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from egosim.world import kernels
from egosim.world.arrays import FloatArray, IntArray
from egosim.world.kernels.lane_projection import project_points
from egosim.world.map.spatial_index import SegmentGrid

# Cost of a candidate lane = distance (m) + HEADING_WEIGHT_M_PER_RAD * heading error: a car
# drifting 1.5 m off its lane still beats a connector crossing it at 90 deg.
HEADING_WEIGHT_M_PER_RAD = 2.0
# Lanes pointing more than 90 deg away from the hint lose to any lane pointing the right way
# within this distance.
WRONG_WAY_PENALTY_M = 50.0
# Bounds the memory of the exhaustive search for points far from every lane.
EXHAUSTIVE_PAIRS_PER_CHUNK = 1_000_000
# Grid cell edge; a point on a road or its kerb finds its lane in the 3 x 3 cells around it.
GRID_CELL_M = 6.0
# Beyond this a coordinate is no place on Earth (|x|, |y| well past any projected map),
# and its grid cell would overflow the compiled loop's integers.
COMPILED_COORDINATE_LIMIT_M = 1.0e9


@dataclass(frozen=True)
class LaneProjection:
    """Where a point lies relative to one lane."""

    lane_id: str
    s: float
    lateral: float
    heading: float
    distance_left: float
    distance_right: float
    width: float


@dataclass(frozen=True, eq=False)
class LaneProjections:
    """LaneProjection for many points, as parallel arrays (lane_index into `lane_ids`)."""

    lane_ids: tuple[str, ...]
    lane_index: IntArray
    s: FloatArray
    lateral: FloatArray
    heading: FloatArray
    distance_left: FloatArray
    distance_right: FloatArray
    width: FloatArray

    def __len__(self) -> int:
        return len(self.lane_index)

    def part(self, start: int, stop: int) -> LaneProjections:
        """The projections of points start..stop-1."""
        return LaneProjections(
            self.lane_ids,
            self.lane_index[start:stop],
            self.s[start:stop],
            self.lateral[start:stop],
            self.heading[start:stop],
            self.distance_left[start:stop],
            self.distance_right[start:stop],
            self.width[start:stop],
        )

    def __getitem__(self, i: int) -> LaneProjection:
        return LaneProjection(
            lane_id=self.lane_ids[int(self.lane_index[i])],
            s=float(self.s[i]),
            lateral=float(self.lateral[i]),
            heading=float(self.heading[i]),
            distance_left=float(self.distance_left[i]),
            distance_right=float(self.distance_right[i]),
            width=float(self.width[i]),
        )


class ProjectionMemory:
    """What a caller projecting the same points step after step (the world, its agents,
    in the same order every step) keeps between projections: the points of its last one
    and what was found for them (see kernels/lane_projection.py's project_points). A
    point that has not moved is copied from here, not searched for; the results are the
    same. One caller's own: the compiled projection updates it in place."""

    def __init__(self, capacity: int = 0) -> None:
        self.capacity = capacity
        self.points = np.empty((capacity, 3))
        """x, y, heading hint of each point."""
        self.lanes = np.empty(capacity, np.int64)
        self.facts = np.empty((6, capacity))
        self.count = np.zeros(1, np.int64)
        """How many of the rows above hold the last call's points."""

    def grow(self, capacity: int) -> None:
        """Room for at least `capacity` points (forgetting the last projection)."""
        self.capacity = max(capacity, 2 * self.capacity)
        self.points = np.empty((self.capacity, 3))
        self.lanes = np.empty(self.capacity, np.int64)
        self.facts = np.empty((6, self.capacity))
        self.count[0] = 0


_NO_MEMORY = ProjectionMemory()
"""For callers that keep none: no room, so nothing is remembered."""


class SegmentTable:
    """All centreline segments of a map, flattened, with the grid that finds them."""

    def __init__(
        self,
        lane_ids: tuple[str, ...],
        centrelines: list[FloatArray],
        stations: list[FloatArray],
        widths: list[FloatArray],
    ) -> None:
        self.lane_ids = lane_ids
        self.start = np.concatenate([c[:-1, :2] for c in centrelines])
        self.delta = np.concatenate([np.diff(c[:, :2], axis=0) for c in centrelines])
        self.length_sq = np.einsum("ij,ij->i", self.delta, self.delta)
        self.length = np.sqrt(self.length_sq)
        self.heading = np.arctan2(self.delta[:, 1], self.delta[:, 0])
        self.lane = np.repeat(np.arange(len(centrelines)), [len(c) - 1 for c in centrelines])
        self.s0 = np.concatenate([s[:-1] for s in stations])
        self.width0 = np.concatenate([w[:-1] for w in widths])
        self.width1 = np.concatenate([w[1:] for w in widths])
        self.grid = SegmentGrid(self.start, self.start + self.delta, GRID_CELL_M)

    def project(
        self, xy: FloatArray, headings: FloatArray | None, memory: ProjectionMemory | None = None
    ) -> LaneProjections:
        """Best lane for each point: least distance + heading error (see module constants);
        a NaN heading hint means none for that point. `memory`: the caller's, from its
        last projection, if it keeps one."""
        n = len(xy)
        if kernels.ACTIVE:
            projected = self._project_compiled(xy, headings, memory or _NO_MEMORY)
            # The compiled loop turns coordinates into grid cells without numpy's checks:
            # it refuses a point that is not finite or is beyond any map (odd input),
            # which the numpy path then places.
            if len(projected) == n:
                return projected
        best_seg = np.zeros(n, dtype=np.int64)
        best_t = np.zeros(n)
        pending = np.arange(n)
        ring = 1
        while pending.size and ring <= self.grid.max_ring:
            hint = None if headings is None else headings[pending]
            point, seg = self.grid.candidates(xy[pending], ring)
            found, seg_best, t_best, cost = self._best_pairs(xy[pending], hint, point, seg)
            # Nothing outside the searched square is nearer than ring cells.
            done = found & (cost <= ring * self.grid.cell_size)
            best_seg[pending[done]] = seg_best[done]
            best_t[pending[done]] = t_best[done]
            pending = pending[~done]
            ring *= 2
        # Points far from every lane: compare against all segments, a few points at a time.
        chunk = max(1, EXHAUSTIVE_PAIRS_PER_CHUNK // len(self.start))
        for first in range(0, pending.size, chunk):
            some = pending[first : first + chunk]
            hint = None if headings is None else headings[some]
            point = np.repeat(np.arange(some.size), len(self.start))
            seg = np.tile(np.arange(len(self.start)), some.size)
            _, best_seg[some], best_t[some], _ = self._best_pairs(xy[some], hint, point, seg)
        return self._describe(xy, best_seg, best_t)

    def _project_compiled(
        self, xy: FloatArray, headings: FloatArray | None, memory: ProjectionMemory
    ) -> LaneProjections:
        """project() in one compiled loop: the same arithmetic, the same results."""
        grid = self.grid
        hints = np.full(len(xy), np.nan) if headings is None else headings
        if memory is not _NO_MEMORY and len(xy) > memory.capacity:
            memory.grow(len(xy))
        lane, (s, lateral, heading, left, right, width) = project_points(
            np.ascontiguousarray(xy),
            np.ascontiguousarray(hints),
            self.start,
            self.delta,
            self.length_sq,
            self.length,
            self.heading,
            self.s0,
            self.width0,
            self.width1,
            self.lane,
            grid.origin,
            grid.cell_size,
            grid.shape,
            grid.segments,
            grid.offsets,
            HEADING_WEIGHT_M_PER_RAD,
            WRONG_WAY_PENALTY_M,
            COMPILED_COORDINATE_LIMIT_M,
            memory.points,
            memory.lanes,
            memory.facts,
            memory.count,
        )
        return LaneProjections(self.lane_ids, lane, s, lateral, heading, left, right, width)

    def _best_pairs(
        self, xy: FloatArray, hint: FloatArray | None, point: IntArray, seg: IntArray
    ) -> tuple[npt.NDArray[np.bool_], IntArray, FloatArray, FloatArray]:
        n = len(xy)
        found = np.zeros(n, dtype=bool)
        seg_best = np.zeros(n, dtype=np.int64)
        t_best = np.zeros(n)
        cost_best = np.full(n, np.inf)
        if point.size == 0:
            return found, seg_best, t_best, cost_best
        rel = xy[point] - self.start[seg]
        delta = self.delta[seg]
        along = np.einsum("ij,ij->i", rel, delta) / self.length_sq[seg]
        t = np.minimum(np.maximum(along, 0.0), 1.0)
        gap = rel - t[:, None] * delta
        cost = np.hypot(gap[:, 0], gap[:, 1])
        if hint is not None:
            error = np.abs(
                np.remainder(self.heading[seg] - hint[point] + math.pi, math.tau) - math.pi
            )
            # fmax turns the NaN error of a point without a hint into no cost.
            cost += np.fmax(HEADING_WEIGHT_M_PER_RAD * error, 0.0) + np.where(
                error > math.pi / 2, WRONG_WAY_PENALTY_M, 0.0
            )
        # Pairs are grouped by point; the first pair reaching each point's minimum wins.
        # Linear in the pairs: large batches (thousands of points) stay cheap too.
        new_group = np.concatenate(([True], point[1:] != point[:-1]))
        group_start = np.flatnonzero(new_group)
        group = np.cumsum(new_group) - 1
        is_min = cost == np.minimum.reduceat(cost, group_start)[group]
        pair = np.arange(len(cost))
        first = np.minimum.reduceat(np.where(is_min, pair, len(cost)), group_start)
        # A point that is not a number (odd input) has no least cost: its first pair.
        first = np.where(first < len(cost), first, group_start)
        points = point[group_start]
        found[points] = True
        seg_best[points] = seg[first]
        t_best[points] = t[first]
        cost_best[points] = cost[first]
        return found, seg_best, t_best, cost_best

    def _describe(self, xy: FloatArray, seg: IntArray, t: FloatArray) -> LaneProjections:
        rel = xy - self.start[seg]
        gap = rel - t[:, None] * self.delta[seg]
        distance = np.hypot(gap[:, 0], gap[:, 1])
        cross = self.delta[seg, 0] * rel[:, 1] - self.delta[seg, 1] * rel[:, 0]
        lateral = np.where(cross >= 0.0, distance, -distance)
        width = self.width0[seg] + t * (self.width1[seg] - self.width0[seg])
        return LaneProjections(
            lane_ids=self.lane_ids,
            lane_index=self.lane[seg],
            s=self.s0[seg] + t * self.length[seg],
            lateral=lateral,
            heading=self.heading[seg],
            distance_left=width / 2.0 - lateral,
            distance_right=width / 2.0 + lateral,
            width=width,
        )
