"""Uniform grid over line segments: which segments may be near a point."""

from __future__ import annotations

import math

import numpy as np

from egosim.world.arrays import FloatArray, IntArray

# Keeps the grid's offset table small on very large maps.
MAX_CELLS = 4_000_000
# Bounds the memory of the per-cell neighbourhoods kept for repeated queries.
MAX_REMEMBERED_CELLS = 100_000


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
        self._near: dict[tuple[int, int, int], IntArray] = {}

    def _cell_of(self, xy: FloatArray) -> IntArray:
        cell: IntArray = np.floor((xy - self.origin) / self.cell_size).astype(np.int64)
        return cell

    @property
    def max_ring(self) -> int:
        """Ring at which every cell of the grid is searched from anywhere inside it."""
        return int(self.shape.max())

    def candidates(self, xy: FloatArray, ring: int) -> tuple[IntArray, IntArray]:
        """(point index, segment index) pairs for the cells within `ring` of each point.

        Pairs are grouped by point in ascending order; no segment repeats for a point.
        """
        cells = self._cell_of(xy).tolist()
        near = [self._near_cell(ix, iy, ring) for ix, iy in cells]
        counts = [len(segments) for segments in near]
        point = np.repeat(np.arange(len(cells)), counts)
        return point, np.concatenate(near) if near else np.empty(0, np.int64)

    def _near_cell(self, ix: int, iy: int, ring: int) -> IntArray:
        """The segments filed within `ring` cells of cell (ix, iy), each once.

        Kept per cell: agents move little between steps, so they ask for the same cells
        again and again.
        """
        key = (ix, iy, ring)
        segments = self._near.get(key)
        if segments is None:
            if len(self._near) >= MAX_REMEMBERED_CELLS:
                self._near.clear()
            x = np.arange(max(ix - ring, 0), min(ix + ring + 1, int(self.shape[0])))
            y = np.arange(max(iy - ring, 0), min(iy + ring + 1, int(self.shape[1])))
            keys = (x[:, None] * self.shape[1] + y).ravel()
            segments = np.unique(
                np.concatenate(
                    [self.segments[self.offsets[k] : self.offsets[k + 1]] for k in keys]
                    or [np.empty(0, np.int64)]
                )
            )
            self._near[key] = segments
        return segments
