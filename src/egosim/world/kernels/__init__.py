"""Compiled kernels of the world step, and the switch between them and plain numpy.

The step's hot parts (lane projection, the NPCs' leader search and IDM, their lane
poses, the swept collision test, the pedestrian step, the ego's dynamics) each have two
paths: the vectorised numpy code, and a loop kernel here compiled by numba. A step is
hundreds of small arrays, so the numpy path pays about 1 µs of per-call overhead many
times over, which a compiled loop does not.

Both paths give bit-identical results: the kernels do the same IEEE operations in the
same order as the numpy code (numba's fastmath off, so no reassociation and no fused
multiply-adds), pick the same element on ties, and use only the functions whose numpy
and libm results agree bit for bit (+ - * /, sqrt, sin, cos, hypot, fmod). Where the
numpy path calls arctan2, arctan, exp or a float power (vectorised differently by numpy
on some CPUs), that call stays in numpy on both paths.

`ACTIVE` says which path runs. It is on where numba imports (a pip wheel: no compiler
is needed) unless the environment sets EGOSIM_COMPILED=0; tests flip it to run one
scenario through both paths. Kernels are compiled on first use and cached on disk
(numba's `cache=True`), so only the first start after an install pays the compile.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from typing import ParamSpec, TypeVar, cast

Parameters = ParamSpec("Parameters")
Result = TypeVar("Result")
Compiler = Callable[[Callable[..., object]], Callable[..., object]]

SWITCH_VARIABLE = "EGOSIM_COMPILED"


def _numba_jit() -> Compiler | None:
    if os.environ.get(SWITCH_VARIABLE, "1").strip().lower() in ("0", "false", "no", "off"):
        return None
    try:
        import numba  # noqa: PLC0415 (optional: no wheel on some platforms)
    except ImportError:
        return None
    jit: Compiler = numba.njit(cache=True, fastmath=False, nogil=True)
    return jit


_JIT = _numba_jit()

AVAILABLE = _JIT is not None
"""numba imported and the environment did not switch the compiled path off."""
ACTIVE = AVAILABLE
"""The compiled path runs (read at every call: tests may switch it off)."""


def kernel(function: Callable[Parameters, Result]) -> Callable[Parameters, Result]:
    """`function` compiled (lazily, on its first call) where numba is available; as
    written elsewhere, though the callers then take the numpy path instead."""
    if _JIT is None:
        return function
    # numba's dispatcher is called as the function it compiles, with the same result.
    return cast(Callable[Parameters, Result], _JIT(function))


__all__ = ["ACTIVE", "AVAILABLE", "SWITCH_VARIABLE", "kernel"]
