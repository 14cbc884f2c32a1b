"""Exceptions of the batch package."""

from __future__ import annotations

from egosim.yamltext import YamlFileError


class SuiteError(YamlFileError):
    """A suite that cannot be run, located by file, line and field."""
