"""Activation distances: road users that stand until an ego comes near (MORAI's active
distance of NPC vehicles and pedestrians)."""

from __future__ import annotations

import numpy as np

from egosim.world.arrays import BoolArray, FloatArray


def still_dormant(
    dormant: BoolArray, centres: FloatArray, reach: FloatArray, points: FloatArray
) -> BoolArray:
    """`dormant` less those whose centre (N, 2) m lies within their `reach` (N,) m of any
    of `points` (K, 2) m; waking is for good, so the caller keeps the result."""
    if not dormant.any() or len(points) == 0:
        return dormant
    offsets = centres[:, None, :2] - np.asarray(points, dtype=np.float64)[None, :, :2]
    nearest = np.min(np.hypot(offsets[..., 0], offsets[..., 1]), axis=1)
    result: BoolArray = dormant & (nearest > reach)
    return result
