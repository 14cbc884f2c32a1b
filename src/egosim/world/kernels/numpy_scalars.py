"""numpy's elementwise semantics on scalars, for kernels that must match numpy's results.

Python's (and numba's) min, max and % differ from np.minimum, np.maximum and
np.remainder on NaN and signed zeros; these do not.
"""

from __future__ import annotations

import math

import numpy as np

from egosim.world.kernels import kernel


@kernel
def maximum(a: float, b: float) -> float:
    """np.maximum: NaN if either is NaN, else the larger (the first on ties)."""
    if a != a or a >= b:  # noqa: PLR0124 (a != a: a is NaN)
        return a
    return b


@kernel
def minimum(a: float, b: float) -> float:
    """np.minimum: NaN if either is NaN, else the smaller (the first on ties)."""
    if a != a or a <= b:  # noqa: PLR0124
        return a
    return b


@kernel
def fmax(a: float, b: float) -> float:
    """np.fmax: the larger, ignoring a NaN unless both are."""
    if b != b or a >= b:  # noqa: PLR0124
        return a
    return b


@kernel
def remainder(a: float, b: float) -> float:
    """np.remainder: a mod b with the sign of b (numpy's npy_divmod)."""
    if b == 0.0:
        return math.nan
    mod = float(np.fmod(a, b))
    if mod != 0.0:
        if (b < 0.0) != (mod < 0.0):
            mod += b
    else:
        mod = math.copysign(0.0, b)
    return mod


@kernel
def clip(a: float, low: float, high: float) -> float:
    """np.minimum(np.maximum(a, low), high)."""
    return minimum(maximum(a, low), high)
