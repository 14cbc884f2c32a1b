"""Pass criteria: `no_collision`, `no_<infraction>`, or `<metric> <op> <number>`."""

from __future__ import annotations

import math
import operator
import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import TypedDict

from egosim.evaluation.infractions import InfractionKind

_COMPARISON = re.compile(r"^\s*([a-z_][a-z0-9_]*)\s*(>=|<=|==|!=|>|<)\s*([-+0-9.eE]+)\s*$")
_OPERATORS: dict[str, Callable[[float, float], bool]] = {
    ">=": operator.ge,
    "<=": operator.le,
    ">": operator.gt,
    "<": operator.lt,
    "==": operator.eq,
    "!=": operator.ne,
}
UNBOUNDED_WHEN_MISSING = frozenset({"min_ttc_s", "min_headway_s"})
"""Minima that are None when nothing was ever ahead: they count as infinite."""


class CriterionError(ValueError):
    """A criterion that cannot be read or names an unknown figure."""


@dataclass(frozen=True)
class Criterion:
    text: str
    metric: str
    compare: str
    threshold: float

    def check(self, metrics: Mapping[str, float | int | None]) -> CriterionResult:
        value = metrics.get(self.metric)
        if value is None and self.metric in UNBOUNDED_WHEN_MISSING:
            value = math.inf
        if value is None:
            return CriterionResult(self.text, False, None, f"{self.metric} is not measured")
        passed = _OPERATORS[self.compare](float(value), self.threshold)
        return CriterionResult(
            self.text, passed, value, "" if passed else f"{self.metric} = {value:.4g}"
        )


class CriterionRecord(TypedDict):
    """A CriterionResult as JSON (results.json)."""

    criterion: str
    passed: bool
    value: float | int | None


@dataclass(frozen=True)
class CriterionResult:
    text: str
    passed: bool
    value: float | int | None
    reason: str = ""

    def as_dict(self) -> CriterionRecord:
        return {"criterion": self.text, "passed": self.passed, "value": self.value}


def parse_criterion(text: str, known_metrics: frozenset[str]) -> Criterion:
    """A Criterion from its text; `known_metrics` are the figures a score holds."""
    name = text.strip()
    if name == "no_collision":
        return Criterion(text, "collisions", "==", 0.0)
    if name.startswith("no_"):
        kinds = {kind.value for kind in InfractionKind}
        kind = name[3:]
        if kind not in kinds:
            raise CriterionError(
                f"unknown criterion {text!r}: no_collision or no_ followed by one of "
                f"{', '.join(sorted(kinds))}"
            )
        return Criterion(text, f"{kind}_count", "==", 0.0)
    match = _COMPARISON.match(text)
    if match is None:
        raise CriterionError(f"cannot read criterion {text!r}: expected 'metric >= number'")
    metric, compare, number = match.groups()
    if metric not in known_metrics:
        known = ", ".join(sorted(known_metrics))
        raise CriterionError(f"unknown figure {metric!r} in criterion {text!r}; known: {known}")
    try:
        threshold = float(number)
    except ValueError:
        raise CriterionError(f"cannot read the number in criterion {text!r}") from None
    return Criterion(text, metric, compare, threshold)
