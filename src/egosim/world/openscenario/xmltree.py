"""OpenSCENARIO XML read with lxml: elements with their file and line, and the errors
and notes that name them.

lxml keeps every element's source line (ElementTree does not), so an error or an
unsupported element is reported as `file:line: <Tag>: ...`. Comments and processing
instructions are skipped; a document that is not well-formed XML is one ScenarioError
at the line the parser names.
"""

from __future__ import annotations

import re
from collections.abc import Iterator

from lxml import etree

from egosim.world.scenario.errors import ScenarioError

_WHERE_SUFFIX = re.compile(r",? line \d+, column \d+$")
# Entities and external DTDs are never resolved (a scenario file comes from the user or
# the network); huge trees are refused by lxml's own limits.
_PARSER = etree.XMLParser(
    resolve_entities=False, no_network=True, remove_comments=True, remove_pis=True
)


class Node:
    """One XML element of a file: tag, attributes, children, and where it is."""

    __slots__ = ("_element", "label")

    def __init__(self, element: etree._Element, label: str) -> None:
        self._element = element
        self.label = label

    @property
    def tag(self) -> str:
        return str(etree.QName(self._element).localname)

    @property
    def line(self) -> int | None:
        line: object = self._element.sourceline
        return line if isinstance(line, int) else None

    @property
    def where(self) -> str:
        return f"{self.label}:{self.line}" if self.line is not None else self.label

    @property
    def attributes(self) -> dict[str, str]:
        return {str(k): str(v) for k, v in self._element.attrib.items()}

    def get(self, name: str) -> str | None:
        value = self._element.get(name)
        return None if value is None else str(value)

    def children(self, tag: str | None = None) -> list[Node]:
        return [
            Node(child, self.label)
            for child in self._element
            if isinstance(child.tag, str) and (tag is None or etree.QName(child).localname == tag)
        ]

    def child(self, tag: str) -> Node | None:
        found = self.children(tag)
        return found[0] if found else None

    def only_child(self) -> Node | None:
        """The element's single child element (a choice such as <Position>'s), if any."""
        found = self.children()
        return found[0] if found else None

    def require(self, tag: str) -> Node:
        found = self.child(tag)
        if found is None:
            raise self.error(f"needs a <{tag}>")
        return found

    def walk(self) -> Iterator[Node]:
        """This element and every element below it, in document order."""
        for element in self._element.iter():
            if isinstance(element.tag, str):
                yield Node(element, self.label)

    def error(self, message: str) -> ScenarioError:
        return ScenarioError(self.label, self.line, f"<{self.tag}>", message)

    def note(self, message: str) -> str:
        """One line naming this element and where it is, for what is read but left out."""
        return f"{self.where}: <{self.tag}> {message}"


def parse_xml(text: str | bytes, label: str) -> Node:
    """The root element of an XML text; ScenarioError if it is not well-formed."""
    data = text.encode("utf-8") if isinstance(text, str) else text
    try:
        root = etree.fromstring(data, _PARSER)
    except etree.XMLSyntaxError as error:
        line = error.lineno if error.lineno else None
        # libxml2 may quote the offending text on further lines: the first one says it.
        lines = (error.msg or "").strip().splitlines() or ["unreadable"]
        reason = _WHERE_SUFFIX.sub("", lines[0].strip())
        raise ScenarioError(label, line, "", f"not well-formed XML: {reason}") from None
    return Node(root, label)
