"""Uniform grid over line segments: which segments may be near a point."""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
import numpy.typing as npt

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]

# Keeps the grid's offset table small on very large maps.
MAX_CELLS = 4_000_000


class SegmentGrid:
    """Each segment is filed under every cell its bounding box touches.

    A segment whose nearest point to a query lies within `ring * cell_size` of the query
    is therefore filed in one of the (2 ring + 1)^2 cells around the query's cell.
    """

    def __init__(self, starts: FloatArray, ends: FloatArray, cell_size: float) -> None:
        lo = np.minimum(starts, ends)
        hi = np.maximum(starts, ends)
        self.origin = lo.min(axis=0) - cell_size
        extent = hi.max(axis=0) + cell_size - self.origin
        area_cell = math.sqrt(float(extent[0] * extent[1]) / MAX_CELLS)
        self.cell_size = max(cell_size, area_cell)
        self.shape = np.ceil(extent / self.cell_size).astype(np.int64) + 1

        cell_lo = self._cell_of(lo)
        cell_hi = self._cell_of(hi)
        spans = cell_hi - cell_lo + 1
        counts = spans[:, 0] * spans[:, 1]
        segment = np.repeat(np.arange(len(starts)), counts)
        local = np.arange(counts.sum()) - np.repeat(np.cumsum(counts) - counts, counts)
        span_y = np.repeat(spans[:, 1], counts)
        ix = np.repeat(cell_lo[:, 0], counts) + local // span_y
        iy = np.repeat(cell_lo[:, 1], counts) + local % span_y
        keys = ix * self.shape[1] + iy
        order = np.argsort(keys, kind="stable")
        self.segments: IntArray = segment[order]
        n_cells = int(self.shape[0] * self.shape[1])
        self.offsets: IntArray = np.concatenate(
            ([0], np.cumsum(np.bincount(keys, minlength=n_cells)))
        )

    def _cell_of(self, xy: FloatArray) -> IntArray:
        return np.floor((xy - self.origin) / self.cell_size).astype(np.int64)

    @property
    def max_ring(self) -> int:
        """Ring at which every cell of the grid is searched from anywhere inside it."""
        return int(self.shape.max())

    def candidates(self, xy: FloatArray, ring: int) -> tuple[IntArray, IntArray]:
        """(point index, segment index) pairs for the cells within `ring` of each point.

        Pairs are grouped by point in ascending order; a segment may repeat.
        """
        dx, dy = _ring_offsets(ring)
        cells = self._cell_of(xy)
        ix = cells[:, :1] + dx
        iy = cells[:, 1:] + dy
        inside = (ix >= 0) & (ix < self.shape[0]) & (iy >= 0) & (iy < self.shape[1])
        keys = np.where(inside, ix * self.shape[1] + iy, 0)
        first = self.offsets[keys]
        counts = np.where(inside, self.offsets[keys + 1] - first, 0).ravel()
        total = int(counts.sum())
        point = np.repeat(np.repeat(np.arange(len(xy)), dx.size), counts)
        local = np.arange(total) - np.repeat(np.cumsum(counts) - counts, counts)
        return point, self.segments[np.repeat(first.ravel(), counts) + local]


@lru_cache(maxsize=32)
def _ring_offsets(ring: int) -> tuple[IntArray, IntArray]:
    """Cell offsets (dx, dy) of the (2 ring + 1)^2 square around a cell."""
    steps = np.arange(-ring, ring + 1)
    dx, dy = np.meshgrid(steps, steps, indexing="ij")
    return dx.ravel(), dy.ravel()
