"""numpy's and Python's scalar semantics, for kernels that must match their results.

numba's min, max and % may differ from np.minimum, np.maximum, np.remainder and from
Python's own min, max and math.remainder on NaN, ties and signed zeros; these do not.
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


@kernel
def python_max(a: float, b: float) -> float:
    """Python's max(a, b) of two floats: the first unless the second is larger."""
    return b if b > a else a


@kernel
def python_min(a: float, b: float) -> float:
    """Python's min(a, b) of two floats: the first unless the second is smaller."""
    return b if b < a else a


@kernel
def ieee_remainder(x: float, y: float) -> float:
    """math.remainder (CPython's m_remainder): x - n y, n the integer nearest x / y, ties
    to even; exact, like the original."""
    if math.isfinite(x) and math.isfinite(y):
        if y == 0.0:
            return math.nan
        absx, absy = abs(x), abs(y)
        m = float(np.fmod(absx, absy))
        c = absy - m
        if m < c:
            r = m
        elif m > c:
            r = -c
        else:
            r = m - 2.0 * float(np.fmod(0.5 * (absx - m), absy))
        return math.copysign(1.0, x) * r
    if x != x:  # noqa: PLR0124
        return x
    if y != y:  # noqa: PLR0124
        return y
    if math.isinf(x):
        return math.nan
    return x
