"""Reading a MORAI scenario document: typed fields at JSON paths, every problem at once,
and a report of what the file asks that egosim does not do, one line per field name.

A problem names the JSON path (`vehicleList[2].DataID`); MORAI's editor writes some
numbers as strings (`"yaw": "-29.315"`, `"1,232.436"`), which read as numbers.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field

from egosim.json_value import JsonObject, JsonValue
from egosim.world.scenario.errors import ScenarioError
from egosim.yamltext import FieldPath, Problems, field_name

MAX_PLACES_LISTED = 5
"""A report line lists this many places of its field, then how many more."""

_NUMBER_TEXT = re.compile(r"[+-]?(\d{1,3}(,\d{3})+|\d+)?(\.\d*)?([eE][+-]?\d+)?")


def always(_: JsonValue) -> bool:
    return True


def switched_on(key: str) -> Callable[[JsonValue], bool]:
    """Matters when the value is an object whose flag `key` is true."""
    return lambda value: isinstance(value, dict) and value.get(key) is True


def truthy(value: JsonValue) -> bool:
    """A value that asks for something: a true flag, a non-zero number, a non-empty list
    or mapping or text."""
    return bool(value)


@dataclass(frozen=True)
class Ignored:
    """A field egosim reads past: why, and which of its values ask for something."""

    reason: str
    matters: Callable[[JsonValue], bool] = always


@dataclass
class Reading:
    """One document being read: its label, the problems found, what is reported."""

    label: str
    problems: Problems = field(default_factory=Problems)
    _report: dict[tuple[str, str], list[str]] = field(default_factory=dict)

    def error(self, path: FieldPath, message: str) -> ScenarioError:
        return ScenarioError(self.label, None, field_name(path), message)

    def fail(self, path: FieldPath, message: str) -> None:
        """Record a problem and carry on (every problem of the file is reported)."""
        self.problems.add(self.error(path, message))

    def report(self, path: FieldPath, message: str) -> None:
        """Say once per field name (list indices left out) that `message` holds there."""
        pattern = field_name(tuple("[]" if isinstance(p, int) else p for p in path))
        places = self._report.setdefault((pattern.replace(".[]", "[]"), message), [])
        places.append(field_name(path[:-1]))

    def lines(self) -> list[str]:
        lines = []
        for (pattern, message), places in self._report.items():
            listed = [p for p in places if p] if "[]" in pattern else []
            where = ", ".join(listed[:MAX_PLACES_LISTED])
            if len(listed) > MAX_PLACES_LISTED:
                where += f" and {len(listed) - MAX_PLACES_LISTED} more"
            lines.append(f"{self.label}: {pattern}: {message}" + (f" ({where})" if where else ""))
        return lines

    def check_fields(
        self,
        data: Mapping[str, JsonValue],
        path: FieldPath,
        read: frozenset[str],
        ignored: Mapping[str, Ignored],
    ) -> None:
        """Report the fields of `data` that are neither `read` nor asking nothing."""
        for key, value in data.items():
            if key in read:
                continue
            rule = ignored.get(key)
            if rule is None:
                self.report((*path, key), "not a field egosim knows; not read")
            elif rule.matters(value):
                self.report((*path, key), f"not carried out: {rule.reason}")


def number(
    r: Reading,
    data: Mapping[str, JsonValue],
    key: str,
    path: FieldPath,
    default: float | None = None,
    minimum: float | None = None,
) -> float | None:
    """A finite number (or numeric text) at data[key]; `default` when it is absent (None:
    the field is required). A problem yields None."""
    where = (*path, key)
    if key not in data:
        if default is None:
            r.fail(where, "missing")
        return default
    value = data[key]
    result = _as_number(value)
    if result is None or not math.isfinite(result):
        r.fail(where, f"{value!r} is not a number")
        return None
    if minimum is not None and result < minimum:
        r.fail(where, f"{value!r} is less than {minimum:g}")
        return None
    return result


def _as_number(value: JsonValue) -> float | None:
    if isinstance(value, bool):
        return None
    if isinstance(value, int | float):
        return float(value)
    if isinstance(value, str) and _NUMBER_TEXT.fullmatch(value.strip()):
        try:
            return float(value.strip().replace(",", ""))
        except ValueError:  # the pattern's empty and "." forms
            return None
    return None


def integer(
    r: Reading, data: Mapping[str, JsonValue], key: str, path: FieldPath, default: int | None = None
) -> int | None:
    if key not in data:
        if default is None:
            r.fail((*path, key), "missing")
        return default
    value = data[key]
    if isinstance(value, bool) or not isinstance(value, int | float) or value != int(value):
        r.fail((*path, key), f"{value!r} is not an integer")
        return None
    return int(value)


def flag(
    r: Reading, data: Mapping[str, JsonValue], key: str, path: FieldPath, default: bool
) -> bool:
    value = data.get(key, default)
    if not isinstance(value, bool):
        r.fail((*path, key), f"{value!r} is not true or false")
        return default
    return value


def text(r: Reading, data: Mapping[str, JsonValue], key: str, path: FieldPath, default: str) -> str:
    value = data.get(key, default)
    if not isinstance(value, str):
        r.fail((*path, key), f"{value!r} is not a string")
        return default
    return value


def mapping(
    r: Reading, data: Mapping[str, JsonValue], key: str, path: FieldPath, required: bool = False
) -> JsonObject | None:
    """The object at data[key]; None when absent (a problem when required)."""
    value = data.get(key)
    if value is None:
        if required:
            r.fail((*path, key), "missing")
        return None
    if not isinstance(value, dict):
        r.fail((*path, key), f"expected an object, got {type(value).__name__}")
        return None
    return value


def entries(
    r: Reading, data: Mapping[str, JsonValue], key: str
) -> list[tuple[FieldPath, JsonObject]]:
    """(path, item) of each object of the top-level list data[key]; items that are not
    objects are problems."""
    value = data.get(key)
    if value is None:
        return []
    if not isinstance(value, list):
        r.fail((key,), f"expected a list, got {type(value).__name__}")
        return []
    found: list[tuple[FieldPath, JsonObject]] = []
    for k, item in enumerate(value):
        if isinstance(item, dict):
            found.append(((key, k), item))
        else:
            r.fail((key, k), f"expected an object, got {type(item).__name__}")
    return found
