"""Exceptions raised by the scenario package."""

from __future__ import annotations

from egosim.yamltext import YamlFileError


class ScenarioError(YamlFileError):
    """A scenario that cannot be used, located by file label, line and field."""
