"""YAML texts whose errors name the file, the line and the field.

Users write scenario and network settings files by hand; "line 12, field
npcs[2].speed" is worth more to them than a traceback.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import yaml

PathKey = tuple[str | int, ...]


class YamlFileError(ValueError):
    """A YAML file is malformed or holds a value it may not hold."""

    def __init__(self, label: str, line: int | None, path: PathKey, problem: str) -> None:
        self.label, self.line, self.path, self.problem = label, line, path, problem
        where = label if line is None else f"{label}:{line}"
        field_name = format_path(path)
        super().__init__(f"{where}: {field_name + ': ' if field_name else ''}{problem}")


def format_path(path: PathKey) -> str:
    text = ""
    for part in path:
        text += f"[{part}]" if isinstance(part, int) else (f".{part}" if text else part)
    return text


@dataclass
class YamlDocument:
    """Plain data parsed from YAML, plus the line of every mapping key and list item."""

    label: str
    data: Any
    lines: dict[PathKey, int] = field(default_factory=dict)

    def error(self, path: PathKey, problem: str) -> YamlFileError:
        """An error pointing at `path`, or at its nearest parent that has a line."""
        for cut in range(len(path), -1, -1):
            if path[:cut] in self.lines:
                return YamlFileError(self.label, self.lines[path[:cut]], path, problem)
        return YamlFileError(self.label, None, path, problem)


def parse_yaml(text: str, label: str) -> YamlDocument:
    """Parse one YAML document (safe loader); syntax errors become YamlFileError."""
    try:
        loader = yaml.SafeLoader(text)
        try:
            node = loader.get_single_node()
            data = loader.construct_document(node) if node is not None else None
        finally:
            loader.dispose()
    except yaml.MarkedYAMLError as exc:
        line = exc.problem_mark.line + 1 if exc.problem_mark else None
        raise YamlFileError(label, line, (), f"invalid YAML: {exc.problem}") from exc
    except yaml.YAMLError as exc:
        raise YamlFileError(label, None, (), f"invalid YAML: {exc}") from exc
    document = YamlDocument(label, data)
    if node is not None:
        _record_lines(node, (), document.lines)
    return document


def _record_lines(node: yaml.Node, path: PathKey, lines: dict[PathKey, int]) -> None:
    lines.setdefault(path, node.start_mark.line + 1)
    if isinstance(node, yaml.MappingNode):
        for key_node, value_node in node.value:
            child = (*path, str(key_node.value))
            lines[child] = key_node.start_mark.line + 1
            _record_lines(value_node, child, lines)
    elif isinstance(node, yaml.SequenceNode):
        for index, item in enumerate(node.value):
            _record_lines(item, (*path, index), lines)
