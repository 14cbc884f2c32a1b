"""YAML text to plain data, remembering the line every value came from."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import yaml

from egosim.world.scenario.errors import ScenarioError

FieldPath = tuple[str | int, ...]


def field_name(path: FieldPath) -> str:
    """`npcs[2].start.lane` for ("npcs", 2, "start", "lane")."""
    text = ""
    for part in path:
        text += f"[{part}]" if isinstance(part, int) else (f".{part}" if text else part)
    return text


@dataclass(frozen=True)
class ScenarioSource:
    """Parsed data plus where each field sits in the file (1-based lines)."""

    label: str
    data: Any
    lines: dict[FieldPath, int] = field(default_factory=dict)

    def line_of(self, path: FieldPath) -> int | None:
        """Line of the deepest located field on `path` (the field itself if it exists)."""
        for end in range(len(path), -1, -1):
            line = self.lines.get(tuple(path[:end]))
            if line is not None:
                return line
        return None

    def error(self, path: FieldPath, message: str) -> ScenarioError:
        return ScenarioError(self.label, self.line_of(path), field_name(path), message)


def read_yaml(text: str, label: str) -> ScenarioSource:
    """Parse YAML (safe subset) keeping each mapping key's and sequence item's line."""
    try:
        root = yaml.compose(text, Loader=yaml.SafeLoader)
    except yaml.MarkedYAMLError as error:
        mark = error.problem_mark or error.context_mark
        line = None if mark is None else mark.line + 1
        raise ScenarioError(label, line, "", f"not valid YAML: {error.problem}") from None
    except yaml.YAMLError as error:
        raise ScenarioError(label, None, "", f"not valid YAML: {error}") from None
    lines: dict[FieldPath, int] = {}
    if root is None:
        return ScenarioSource(label, None, lines)
    constructor = yaml.SafeLoader("")

    def convert(node: yaml.Node, path: FieldPath) -> Any:
        lines[path] = node.start_mark.line + 1
        if isinstance(node, yaml.MappingNode):
            result: dict[Any, Any] = {}
            for key_node, value_node in node.value:
                key = constructor.construct_object(key_node, deep=True)
                if key in result:
                    raise ScenarioError(
                        label,
                        key_node.start_mark.line + 1,
                        field_name((*path, key)),
                        "appears twice",
                    )
                result[key] = convert(value_node, (*path, key))
                lines[(*path, key)] = key_node.start_mark.line + 1
            return result
        if isinstance(node, yaml.SequenceNode):
            return [convert(item, (*path, k)) for k, item in enumerate(node.value)]
        try:
            return constructor.construct_object(node, deep=True)
        except yaml.YAMLError as error:
            raise ScenarioError(
                label, node.start_mark.line + 1, field_name(path), f"bad value: {error}"
            ) from None

    return ScenarioSource(label, convert(root, ()), lines)
