"""Parameter sweeps: lists, ranges and Cartesian products -> concrete parameter sets,
each with a stable name."""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping, Sequence

Value = float | int | str | bool
MAX_CASES = 1_000_000


def distribution_values(spec: Sequence[Value] | Mapping[str, float]) -> list[Value]:
    """A list as it is; {from, to, step}: from, from + step, ... up to `to` inclusive."""
    if not isinstance(spec, Mapping):
        return list(spec)
    start, stop, step = float(spec["from"]), float(spec["to"]), float(spec["step"])
    count = math.floor((stop - start) / step + 1e-9) + 1
    if count > MAX_CASES:
        raise ValueError(f"range of {count} values")
    values = [start + k * step for k in range(max(count, 0))]
    integral = all(float(v).is_integer() for v in (start, step))
    return [int(v) if integral else round(v, 12) for v in values]


def parameter_sets(
    sweep: Mapping[str, Sequence[Value] | Mapping[str, float]] | None,
    combinations: Sequence[Mapping[str, Value]] | None,
) -> list[dict[str, Value]]:
    """Every combination of the sweep's values (in the file's order) for each explicit
    combination; [{}] when there are neither."""
    sweep = sweep or {}
    names = list(sweep)
    grids = [distribution_values(sweep[name]) for name in names]
    size = math.prod(len(g) for g in grids) * max(len(combinations or ()), 1)
    if size > MAX_CASES:
        raise ValueError(f"{size} combinations (at most {MAX_CASES})")
    product = [dict(zip(names, values, strict=True)) for values in itertools.product(*grids)]
    explicit = [dict(c) for c in combinations] if combinations else [{}]
    return [{**fixed, **swept} for fixed in explicit for swept in product]


def format_value(value: Value) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return format(value, "g")
    return str(value)


def case_name(base: str, parameters: Mapping[str, Value]) -> str:
    """`base[k1=v1,k2=v2]` (parameters in their order), or `base` without parameters."""
    if not parameters:
        return base
    inside = ",".join(f"{k}={format_value(v)}" for k, v in parameters.items())
    return f"{base}[{inside}]"
