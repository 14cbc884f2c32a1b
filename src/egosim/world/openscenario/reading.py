"""Reading an element's attributes in a parameter scope: typed values, errors that name
the file, line, element and attribute."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TypeVar

from egosim.world.openscenario.expressions import Value
from egosim.world.openscenario.parameters import Scope, text_of
from egosim.world.openscenario.xmltree import Node

T = TypeVar("T")
_MISSING = object()


class Element:
    """An element read in a scope: `element.number("value")` etc."""

    __slots__ = ("node", "scope")

    def __init__(self, node: Node, scope: Scope) -> None:
        self.node = node
        self.scope = scope

    @property
    def tag(self) -> str:
        return self.node.tag

    def _raw(self, name: str) -> Value | None:
        text = self.node.get(name)
        return None if text is None else self.scope.resolve(text, self.node, name)

    def has(self, name: str) -> bool:
        return self.node.get(name) is not None

    def text(self, name: str, default: str | object | None = _MISSING) -> str:
        value = self._raw(name)
        if value is None:
            if default is _MISSING:
                raise self.node.error(f"needs attribute {name!r}")
            return default  # type: ignore[return-value]
        return text_of(value)

    def optional_text(self, name: str) -> str | None:
        value = self._raw(name)
        return None if value is None else text_of(value)

    def number(self, name: str, default: float | object = _MISSING, finite: bool = True) -> float:
        """The attribute as a number; infinity only where `finite` is false (a limit, a
        condition's value), since a position or a speed of INF is no place to be."""
        value = self._raw(name)
        if value is None:
            if default is _MISSING:
                raise self.node.error(f"needs attribute {name!r}")
            return default  # type: ignore[return-value]
        try:
            number = float(value)
        except ValueError:
            raise self.node.error(f"{name}: {value!r} is not a number") from None
        if math.isnan(number):
            raise self.node.error(f"{name} is not a number")
        if finite and math.isinf(number):
            raise self.node.error(f"{name}: {value!r} is not a finite number")
        return number

    def optional_number(self, name: str) -> float | None:
        return None if self.node.get(name) is None else self.number(name)

    def integer(self, name: str, default: int | object = _MISSING) -> int:
        if self.node.get(name) is None and default is not _MISSING:
            return default  # type: ignore[return-value]
        number = self.number(name)
        if not math.isfinite(number):
            raise self.node.error(f"{name} is not a whole number")
        return math.floor(number + 0.5)

    def boolean(self, name: str, default: bool | object = _MISSING) -> bool:
        value = self._raw(name)
        if value is None:
            if default is _MISSING:
                raise self.node.error(f"needs attribute {name!r}")
            return bool(default)
        if isinstance(value, bool):
            return value
        text = text_of(value).strip().lower()
        if text not in ("true", "false", "1", "0"):
            raise self.node.error(f"{name}: {value!r} is not true or false")
        return text in ("true", "1")

    def choice(self, name: str, options: Sequence[str], default: str | object = _MISSING) -> str:
        value = self.text(name, default)
        if value not in options:
            raise self.node.error(f"{name}: {value!r} is not one of {', '.join(options)}")
        return value

    def child(self, tag: str) -> Element | None:
        node = self.node.child(tag)
        return None if node is None else Element(node, self.scope)

    def require(self, tag: str) -> Element:
        return Element(self.node.require(tag), self.scope)

    def children(self, tag: str | None = None) -> list[Element]:
        return [Element(n, self.scope) for n in self.node.children(tag)]

    def only_child(self) -> Element | None:
        node = self.node.only_child()
        return None if node is None else Element(node, self.scope)

    def with_scope(self, scope: Scope) -> Element:
        return Element(self.node, scope)
