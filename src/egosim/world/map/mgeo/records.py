"""Typed access to the records of an MGeo JSON file, failing with the file and record named."""

from __future__ import annotations

import numpy as np

from egosim.json_value import JsonObject
from egosim.world.arrays import FloatArray
from egosim.world.map.errors import MapRecordError


class Record:
    """One JSON object of an MGeo file (a link, a node, a light...)."""

    __slots__ = ("data", "label", "source")

    def __init__(self, source: str, position: int, data: object) -> None:
        self.source = source
        if not isinstance(data, dict):
            raise MapRecordError(source, f"record #{position}", "is not a JSON object")
        self.data: JsonObject = data
        self.label = f"record #{position} (idx {data.get('idx')!r})"

    def fail(self, reason: str) -> MapRecordError:
        return MapRecordError(self.source, self.label, reason)

    @property
    def idx(self) -> str:
        value = self.data.get("idx")
        if value is None or isinstance(value, (bool, dict, list)) or value == "":
            raise self.fail("has no idx")
        return str(value)

    def text(self, key: str) -> str | None:
        """A string field, or None when absent, null or empty; numbers are read as text."""
        value = self.data.get(key)
        if value is None or value == "":
            return None
        if isinstance(value, (bool, dict, list)):
            raise self.fail(f"{key} must be a string, got {value!r}")
        return str(value)

    def number(self, key: str) -> float | None:
        """A numeric field (numbers as strings accepted), or None when absent, null or empty."""
        value = self.data.get(key)
        if value is None or value == "":
            return None
        try:
            if isinstance(value, bool | list | dict):
                raise ValueError
            result = float(value)
        except (TypeError, ValueError):
            raise self.fail(f"{key} must be a number, got {value!r}") from None
        if not np.isfinite(result):
            raise self.fail(f"{key} must be finite, got {value!r}")
        return result

    def flag(self, key: str) -> bool:
        value = self.data.get(key, False)
        if value is None:
            return False
        if not isinstance(value, bool):
            raise self.fail(f"{key} must be true or false, got {value!r}")
        return value

    def ids(self, key: str) -> tuple[str, ...]:
        """A list of idx references (a single idx is read as a list of one)."""
        value = self.data.get(key)
        if value is None or value == "":
            return ()
        if not isinstance(value, list):
            value = [value]
        if any(v is None or isinstance(v, (bool, dict, list)) for v in value):
            raise self.fail(f"{key} must list idx values, got {value!r}")
        return tuple(str(v) for v in value if v != "")

    def point(self, key: str) -> FloatArray:
        """An [x, y] or [x, y, z] point as a (3,) array."""
        point: FloatArray = self.points(key, single=True)[0]
        return point

    def points(self, key: str, single: bool = False) -> FloatArray:
        """An (N, 3) array from [[x, y, z], ...] (z = 0 for [x, y] points)."""
        value = self.data.get(key)
        if value is None:
            raise self.fail(f"has no {key}")
        try:
            array = np.array([value] if single else value, dtype=np.float64)
        except (TypeError, ValueError):
            raise self.fail(f"{key} must hold [x, y, z] numbers") from None
        if array.ndim != 2 or array.shape[1] not in (2, 3) or not np.all(np.isfinite(array)):
            raise self.fail(f"{key} must hold finite [x, y, z] points")
        if array.shape[1] == 2:
            array = np.column_stack((array, np.zeros(len(array))))
        return array


def records(source: str, data: object) -> list[Record]:
    """The records of a file holding a JSON list of objects."""
    if not isinstance(data, list):
        raise MapRecordError(source, "file", "must hold a JSON list of records")
    return [Record(source, position, item) for position, item in enumerate(data)]


def unique_by_idx(items: list[Record]) -> dict[str, Record]:
    by_idx: dict[str, Record] = {}
    for record in items:
        if record.idx in by_idx:
            raise record.fail("repeats an idx already used in this file")
        by_idx[record.idx] = record
    return by_idx
