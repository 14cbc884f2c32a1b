"""3-vectors as plain float tuples, for the sensors' few vectors per reading.

On plain floats these cost a tenth of numpy's per-call overhead, with the same IEEE
operations in the same order (elementwise adds, np.cross), hence the same bits.
"""

from __future__ import annotations

from collections.abc import Sequence

from egosim.world.arrays import FloatArray

Vector3Tuple = tuple[float, float, float]


def floats3(vector: Sequence[float] | FloatArray) -> Vector3Tuple:
    return (float(vector[0]), float(vector[1]), float(vector[2]))


def add3(first: Vector3Tuple, *others: Vector3Tuple) -> Vector3Tuple:
    """Left to right, as numpy evaluates a + b + c."""
    x, y, z = first
    for other_x, other_y, other_z in others:
        x, y, z = x + other_x, y + other_y, z + other_z
    return (x, y, z)


def cross3(a: Sequence[float], b: Sequence[float]) -> Vector3Tuple:
    """a x b, term by term as np.cross computes it."""
    a0, a1, a2 = floats3(a)
    b0, b1, b2 = floats3(b)
    return (a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0)
