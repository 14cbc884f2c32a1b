"""Exceptions raised by the scenario package."""

from __future__ import annotations


class ScenarioError(ValueError):
    """A scenario that cannot be used, located by file label, line and field."""

    def __init__(self, label: str, line: int | None, field: str, message: str) -> None:
        self.label = label
        self.line = line
        self.field = field
        self.message = message
        where = label if line is None else f"{label}:{line}"
        super().__init__(f"{where}: {field or '(top level)'}: {message}")
