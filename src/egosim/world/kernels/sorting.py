"""A stable argsort for kernels: numpy's np.lexsort((secondary, primary)) order (by an
integer key, then a float key with NaN last, then position), by a bottom-up merge sort;
and the same order of one float key reached from an earlier order of it (a step's boxes
barely move, so last step's order is nearly sorted).

numba's own stable argsort gives the same order but takes several times longer to
compile than every kernel of the step together.
"""

from __future__ import annotations

import numpy as np

from egosim.world.arrays import FloatArray, IntArray
from egosim.world.kernels import kernel

_RUN = 16
"""Length of the runs sorted by insertion before merging."""


@kernel
def _before(primary: IntArray, secondary: FloatArray, a: int, b: int) -> bool:
    """Element a may stay before element b (a was before b)."""
    if primary[a] != primary[b]:
        return bool(primary[a] < primary[b])
    x, y = secondary[a], secondary[b]
    return bool(x <= y or y != y)  # noqa: PLR0124 (y != y: NaN sorts last)


@kernel
def lexsort_argsort(primary: IntArray, secondary: FloatArray) -> IntArray:
    """Indices ordering the elements by primary, then secondary, then position."""
    n = primary.shape[0]
    order = np.arange(n)
    # Runs of RUN elements by insertion first (a stable sort's order is unique, so how
    # it is reached does not change it): fewer passes of the merge below.
    for start in range(0, n, _RUN):
        for k in range(start + 1, min(start + _RUN, n)):
            moving = order[k]
            j = k
            while j > start and not _before(primary, secondary, order[j - 1], moving):
                order[j] = order[j - 1]
                j -= 1
            order[j] = moving
    spare = np.empty(n, dtype=np.int64)
    width = _RUN
    while width < n:
        for start in range(0, n, 2 * width):
            middle, stop = min(start + width, n), min(start + 2 * width, n)
            i, j = start, middle
            for k in range(start, stop):
                if i < middle and (j >= stop or _before(primary, secondary, order[i], order[j])):
                    spare[k] = order[i]
                    i += 1
                else:
                    spare[k] = order[j]
                    j += 1
        order, spare = spare, order
        width *= 2
    return order


_RESORT_MOVES_PER_ELEMENT = 8
"""resort's insertion moves allowed per element before it sorts afresh instead (an order
far from the new one would make the insertion quadratic)."""


@kernel
def _precedes(keys: FloatArray, a: int, b: int) -> bool:
    """Element a comes before element b in a stable sort of `keys` (NaN last)."""
    x, y = keys[a], keys[b]
    if x < y:
        return True
    if x > y:
        return False
    x_nan, y_nan = x != x, y != y  # noqa: PLR0124
    if x_nan != y_nan:
        return bool(y_nan)
    return a < b


@kernel
def resort(keys: FloatArray, earlier: IntArray) -> IntArray:
    """np.argsort(keys, kind="stable"), reached by insertion from `earlier` (a
    permutation of the indices, e.g. the order of the keys a step ago); from scratch
    when `earlier` does not fit or is far from the order."""
    n = keys.shape[0]
    if earlier.shape[0] != n:
        return lexsort_argsort(np.zeros(n, dtype=np.int64), keys)
    order: IntArray = earlier.copy()
    budget = _RESORT_MOVES_PER_ELEMENT * n
    for k in range(1, n):
        moving = order[k]
        j = k
        while j > 0 and _precedes(keys, moving, order[j - 1]):
            order[j] = order[j - 1]
            j -= 1
            budget -= 1
        order[j] = moving
        if budget < 0:
            return lexsort_argsort(np.zeros(n, dtype=np.int64), keys)
    return order


@kernel
def _less(a: float, b: float) -> bool:
    """numpy's sort order: a before b, NaN after every number."""
    return a < b or (b != b and a == a)  # noqa: PLR0124


_NEAR_STEPS = 4
"""How far search_sorted_near walks from its guess before it searches the whole array."""


@kernel
def goes_before(element: float, value: float, right: bool) -> bool:
    """`element` lies before where np.searchsorted puts `value` (on its side): in a
    sorted array, the searchsorted answer is the count of elements that do."""
    return not _less(value, element) if right else _less(element, value)


@kernel
def search_sorted_near(values: FloatArray | IntArray, value: float, right: bool, guess: int) -> int:
    """search_sorted, first trying `guess` and the few places after it (where the answer
    was a step ago, for a value that moves on a little); the answer is the same."""
    n = values.shape[0]
    if 0 <= guess <= n and (guess == 0 or goes_before(values[guess - 1], value, right)):
        place = guess
        for _ in range(_NEAR_STEPS):
            if place == n or not goes_before(values[place], value, right):
                return place
            place += 1
    return search_sorted(values, value, right)


@kernel
def search_sorted(values: FloatArray | IntArray, value: float, right: bool) -> int:
    """np.searchsorted(values, value, side="right" if right else "left") on sorted values
    (numba's own is far slower to compile)."""
    low, high = 0, values.shape[0]
    while low < high:
        middle = (low + high) // 2
        if _less(value, values[middle]) if right else not _less(values[middle], value):
            high = middle
        else:
            low = middle + 1
    return low
