"""Array type aliases shared by the world and the sensors."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]
BoolArray = npt.NDArray[np.bool_]

Indices = int | Sequence[int] | IntArray
"""Which rows of per-agent arrays: one index, a list of them or an index array."""
