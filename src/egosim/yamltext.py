"""YAML texts whose errors name the file, the line and the field.

Users write scenario and network settings files by hand; "line 12, field
npcs[2].speed" is worth more to them than a traceback.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import cast

import yaml

from egosim.json_value import JsonObject, JsonValue

FieldPath = tuple[str | int, ...]

# Bounds on what a document may hold, aliases expanded: far beyond any scenario or
# network settings file, far below what would stall the simulator.
MAX_VALUES = 200_000
MAX_DEPTH = 100


def field_name(path: FieldPath) -> str:
    """`npcs[2].start.lane` for ("npcs", 2, "start", "lane")."""
    text = ""
    for part in path:
        text += f"[{part}]" if isinstance(part, int) else (f".{part}" if text else str(part))
    return text


class YamlFileError(ValueError):
    """A YAML file that cannot be used, located by file label, line and field.

    One error may report several problems of the same file (`problems`, in file order;
    its message has one line each); its own label, line and field are the first one's.
    """

    def __init__(self, label: str, line: int | None, field: str, message: str) -> None:
        self.label = label
        self.line = line
        self.field = field
        self.message = message
        self.problems: tuple[YamlFileError, ...] = (self,)
        where = label if line is None else f"{label}:{line}"
        super().__init__(f"{where}: {field + ': ' if field else ''}{message}")

    @classmethod
    def of_all(cls, errors: Sequence[YamlFileError]) -> YamlFileError:
        """One error reporting every problem of `errors` (each once), in file order."""
        unique: dict[str, YamlFileError] = {}
        for error in errors:
            for problem in error.problems:
                unique.setdefault(str(problem), problem)
        ordered = sorted(unique.values(), key=lambda p: (p.line is None, p.line or 0))
        if len(ordered) == 1:
            return ordered[0]
        first = ordered[0]
        combined = type(first)(first.label, first.line, first.field, first.message)
        combined.problems = tuple(ordered)
        combined.args = ("\n".join(str(problem) for problem in ordered),)
        return combined


class Problems:
    """Collects the problems found in a file, so that they are all reported at once.

    Each independent check runs in its own `with problems.collecting():` block, which
    keeps the YamlFileError it raises and carries on after the block.
    """

    def __init__(self) -> None:
        self.found: list[YamlFileError] = []

    def add(self, error: YamlFileError) -> None:
        self.found.append(error)

    @contextmanager
    def collecting(self) -> Iterator[None]:
        try:
            yield
        except YamlFileError as error:
            self.found.append(error)

    def raise_any(self) -> None:
        if self.found:
            raise YamlFileError.of_all(self.found)


@dataclass(frozen=True)
class YamlDocument:
    """Plain data parsed from YAML, plus where each field sits in the file (1-based lines)."""

    label: str
    data: JsonValue
    lines: dict[FieldPath, int] = field(default_factory=dict)
    error_type: type[YamlFileError] = YamlFileError

    def line_of(self, path: FieldPath) -> int | None:
        """Line of the deepest located field on `path` (the field itself if it exists)."""
        for end in range(len(path), -1, -1):
            line = self.lines.get(tuple(path[:end]))
            if line is not None:
                return line
        return None

    def error(self, path: FieldPath, message: str) -> YamlFileError:
        """An error pointing at `path`, or at its nearest parent that has a line."""
        return self.error_type(self.label, self.line_of(path), field_name(path), message)


def check_nesting(text: str, label: str, error_type: type[YamlFileError]) -> None:
    """Refuse collections nested deeper than MAX_DEPTH before the (recursive) composer
    builds them: it would exhaust Python's stack on a few kilobytes of brackets."""
    depth = 0
    for event in yaml.parse(text, Loader=yaml.SafeLoader):
        if isinstance(event, yaml.CollectionStartEvent):
            depth += 1
            if depth > MAX_DEPTH:
                mark = event.start_mark
                line = None if mark is None else mark.line + 1
                raise error_type(label, line, "", f"nested deeper than {MAX_DEPTH} levels")
        elif isinstance(event, yaml.CollectionEndEvent):
            depth -= 1


def parse_yaml(
    text: str, label: str, error_type: type[YamlFileError] = YamlFileError
) -> YamlDocument:
    """Parse one YAML document (safe subset) keeping each key's and item's line.

    Syntax errors, repeated keys and values YAML cannot build raise `error_type`.
    """
    try:
        check_nesting(text, label, error_type)
        root = yaml.compose(text, Loader=yaml.SafeLoader)
    except yaml.MarkedYAMLError as error:
        mark = error.problem_mark or error.context_mark
        line = None if mark is None else mark.line + 1
        raise error_type(label, line, "", f"not valid YAML: {error.problem}") from None
    except yaml.YAMLError as error:
        raise error_type(label, None, "", f"not valid YAML: {error}") from None
    lines: dict[FieldPath, int] = {}
    if root is None:
        return YamlDocument(label, None, lines, error_type)
    constructor = yaml.SafeLoader("")
    budget = [MAX_VALUES]
    ancestors: set[int] = set()

    def convert(node: yaml.Node, path: FieldPath) -> JsonValue:
        line = node.start_mark.line + 1
        lines[path] = line
        # Aliases make a graph of a few lines expand without bound, or loop.
        budget[0] -= 1
        if budget[0] < 0:
            raise error_type(label, line, field_name(path), f"more than {MAX_VALUES} values")
        if id(node) in ancestors or len(ancestors) >= MAX_DEPTH:
            raise error_type(label, line, field_name(path), "nested too deep (or in itself)")
        if isinstance(node, yaml.MappingNode | yaml.SequenceNode):
            ancestors.add(id(node))
            try:
                return convert_collection(node, path)
            finally:
                ancestors.discard(id(node))
        return construct(node, path)

    def convert_collection(node: yaml.Node, path: FieldPath) -> JsonValue:
        if isinstance(node, yaml.SequenceNode):
            return [convert(item, (*path, k)) for k, item in enumerate(node.value)]
        result: JsonObject = {}
        for key_node, value_node in node.value:
            key_line = key_node.start_mark.line + 1
            if not isinstance(key_node, yaml.ScalarNode):
                raise error_type(label, key_line, field_name(path), "a key must be a plain value")
            # A plain key that reads as a number or a flag stays one (`1: x`), as YAML
            # builds it; readers compare keys with the names they know, so it is unknown.
            key = cast(str, construct(key_node, path))
            # Named once: mypy (run by Python >= 3.11) misreads `lines[(*path, key)]` as
            # Python 3.11's unparenthesised star index when checking for Python 3.10.
            key_path = (*path, key)
            if key in result:
                raise error_type(label, key_line, field_name(key_path), "appears twice")
            result[key] = convert(value_node, key_path)
            lines[key_path] = key_line
        return result

    def construct(node: yaml.Node, path: FieldPath) -> JsonValue:
        try:
            # YAML's safe scalars beyond JSON's (dates, binary) are kept as built: every
            # reader checks a value's type before it uses it, and refuses those.
            return cast(JsonValue, constructor.construct_object(node, deep=True))
        except (yaml.YAMLError, ValueError) as error:
            # ValueError: e.g. an int of more digits than Python converts.
            line = node.start_mark.line + 1
            raise error_type(label, line, field_name(path), f"bad value: {error}") from None

    return YamlDocument(label, convert(root, ()), lines, error_type)


# Typed reads of a document's tree. For a document already checked against its schema
# these only narrow; a value of another type is the reader's mistake, not the user's.


def as_object(value: JsonValue) -> JsonObject:
    """`value` as a mapping (TypeError if it is not one)."""
    if not isinstance(value, dict):
        raise TypeError(f"expected a mapping, got {value!r}")
    return value


def as_list(value: JsonValue) -> list[JsonValue]:
    """`value` as a list (TypeError if it is not one)."""
    if not isinstance(value, list):
        raise TypeError(f"expected a list, got {value!r}")
    return value


def as_number(value: JsonValue) -> float:
    """`value` as a float: an int or a float, never a flag (TypeError otherwise)."""
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise TypeError(f"expected a number, got {value!r}")
    return float(value)


def as_text(value: JsonValue) -> str:
    """`value` as a string (TypeError if it is not one)."""
    if not isinstance(value, str):
        raise TypeError(f"expected a string, got {value!r}")
    return value


def object_at(data: JsonObject, key: str) -> JsonObject | None:
    """The mapping at data[key]; None when the key is absent or null."""
    value = data.get(key)
    return None if value is None else as_object(value)


def list_at(data: JsonObject, key: str) -> list[JsonValue]:
    """The list at data[key]; empty when the key is absent or null."""
    value = data.get(key)
    return [] if value is None else as_list(value)


def objects_at(data: JsonObject, key: str) -> list[JsonObject]:
    """The mappings listed at data[key]; empty when the key is absent or null."""
    return [as_object(item) for item in list_at(data, key)]


def number_at(data: JsonObject, key: str, default: float | None = None) -> float:
    """The number at data[key], as a float; `default` when absent (None: required)."""
    value = data.get(key)
    if value is None and default is not None:
        return default
    return as_number(value)


def optional_number_at(data: JsonObject, key: str) -> float | None:
    """The number at data[key], as a float; None when the key is absent or null."""
    value = data.get(key)
    return None if value is None else as_number(value)


def integer_at(data: JsonObject, key: str, default: int | None = None) -> int:
    """The integer at data[key] (JSON Schema's integers include 2.0); `default` when
    absent (None: required)."""
    value = data.get(key)
    if value is None and default is not None:
        return default
    if isinstance(value, int) and not isinstance(value, bool):
        return value
    if isinstance(value, float) and value.is_integer():
        return int(value)
    raise TypeError(f"{key}: expected an integer, got {value!r}")


def text_at(data: JsonObject, key: str, default: str | None = None) -> str:
    """The string at data[key]; `default` when absent (None: required)."""
    value = data.get(key)
    if value is None and default is not None:
        return default
    return as_text(value)


def optional_text_at(data: JsonObject, key: str) -> str | None:
    """The string at data[key]; None when the key is absent or null."""
    value = data.get(key)
    return None if value is None else as_text(value)


def flag_at(data: JsonObject, key: str, default: bool) -> bool:
    """The true or false at data[key]; `default` when absent or null."""
    value = data.get(key)
    if value is None:
        return default
    if not isinstance(value, bool):
        raise TypeError(f"{key}: expected true or false, got {value!r}")
    return value
