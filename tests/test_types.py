"""docs/ARCHITECTURE.md's Types: `typing.Any` is left only where the data has no type to
give. A module outside the list below that uses it fails here, and so does a module on
the list that no longer needs it."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

import egosim

PACKAGE = Path(egosim.__file__).resolve().parent
TYPING_MODULES = ("typing", "typing_extensions")

MAY_USE_ANY = {
    # The XML-RPC boundary: values of any XML-RPC type, as the ROS master and slave APIs
    # and the parameter server pass them.
    "ros1/master.py",
    "ros1/master_client.py",
    "ros1/node.py",
    "ros1/notifier.py",
    "ros1/param_tree.py",
    "ros1/rpc.py",
    "ros1/slave_api.py",
}


def uses_any(source: str) -> bool:
    """Whether Python `source` imports typing's Any or reads it from the typing module."""
    tree = ast.parse(source)
    typing_names: set[str] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.module in TYPING_MODULES:
            if any(alias.name == "Any" for alias in node.names):
                return True
        elif isinstance(node, ast.Import):
            typing_names |= {a.asname or a.name for a in node.names if a.name in TYPING_MODULES}
    return any(
        isinstance(node, ast.Attribute)
        and node.attr == "Any"
        and isinstance(node.value, ast.Name)
        and node.value.id in typing_names
        for node in ast.walk(tree)
    )


def modules_using_any() -> set[str]:
    return {
        path.relative_to(PACKAGE).as_posix()
        for path in PACKAGE.rglob("*.py")
        if uses_any(path.read_text(encoding="utf-8"))
    }


@pytest.mark.parametrize(
    ("source", "found"),
    [
        ("from typing import Any\n", True),
        ("from typing import TYPE_CHECKING, Any as Anything\n", True),
        ("import typing\nx: typing.Any = 1\n", True),
        ("import typing_extensions as te\ndef f() -> te.Any: ...\n", True),
        ("from typing import Protocol\n'''Any run serves it.'''\nAny = 1\n", False),
        ("import typing\nx: typing.Mapping[str, object] = {}\n", False),
    ],
)
def test_a_use_of_any_is_recognised(source: str, found: bool) -> None:
    assert uses_any(source) is found


def test_any_is_used_only_where_the_data_has_no_type() -> None:
    assert sorted(modules_using_any() - MAY_USE_ANY) == [], "typing.Any outside the list"


def test_the_list_holds_only_modules_that_still_use_any() -> None:
    assert sorted(MAY_USE_ANY - modules_using_any()) == [], "typed now: take it off the list"
