"""Piecewise cubic polynomials of OpenDRIVE records (lane widths, lane offsets, elevation)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from egosim.world.arrays import FloatArray


@dataclass(frozen=True)
class Cubic:
    """a + b·ds + c·ds² + d·ds³ with ds = s - start, valid from `start` to the next record."""

    start: float
    a: float
    b: float
    c: float
    d: float


def evaluate(records: tuple[Cubic, ...], s: FloatArray, outside: float = 0.0) -> FloatArray:
    """The piecewise polynomial at each s (records sorted by start); `outside` before the first."""
    if not records:
        return np.full(np.shape(s), outside)
    starts = np.array([r.start for r in records])
    k = np.searchsorted(starts, s, side="right") - 1
    coefficients = np.array([(r.a, r.b, r.c, r.d) for r in records])[np.maximum(k, 0)]
    ds = s - starts[np.maximum(k, 0)]
    value = coefficients[:, 0] + ds * (
        coefficients[:, 1] + ds * (coefficients[:, 2] + ds * coefficients[:, 3])
    )
    return np.where(k >= 0, value, outside)
