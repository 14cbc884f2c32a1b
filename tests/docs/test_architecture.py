"""docs/ARCHITECTURE.md names what the code has: every package and module of egosim in
its layer list, every module and handler package of the bridge, every field of the
context handlers see. A module added without a word in the document fails here."""

from __future__ import annotations

import dataclasses
import re
from pathlib import Path

import egosim
from egosim.bridge.context import BridgeContext, SessionState

ARCHITECTURE = Path(__file__).resolve().parents[2] / "docs" / "ARCHITECTURE.md"
PACKAGE = Path(egosim.__file__).resolve().parent
NOT_MODULES = {"__init__.py", "__main__.py"}


def section(title: str) -> str:
    text = ARCHITECTURE.read_text(encoding="utf-8")
    start = text.index(f"\n## {title}\n")
    end = text.find("\n## ", start + 1)
    return text[start : end if end != -1 else len(text)]


def layer_entries() -> dict[str, str]:
    """The layer list's entries: `egosim/<name>` -> the text describing it."""
    block = section("Layers (imports point downward only)").split("```")[1]
    entries: dict[str, str] = {}
    name = ""
    for line in block.splitlines():
        if match := re.match(r"egosim/(\S+)\s*(.*)", line):
            name = match.group(1).rstrip("/")
            entries[name] = match.group(2)
        elif name:
            entries[name] += " " + line.strip()
    return entries


def parts_of(folder: Path) -> set[str]:
    """A package's modules (name.py) and subpackages (name/)."""
    return {
        path.name if path.is_file() else path.name + "/"
        for path in folder.iterdir()
        if (path.suffix == ".py" and path.name not in NOT_MODULES)
        or (path.is_dir() and any(path.glob("*.py")))
    }


def test_the_layer_list_names_every_package_and_module_and_nothing_else() -> None:
    listed = {name.removesuffix(".py") for name in layer_entries()}
    present = {part.removesuffix(".py").rstrip("/") for part in parts_of(PACKAGE)}
    assert sorted(present - listed) == [], "in egosim/ but not in ARCHITECTURE.md's layers"
    assert sorted(listed - present) == [], "in ARCHITECTURE.md's layers but not in egosim/"


def test_the_bridge_entry_names_every_module_and_handler_package() -> None:
    bridge = layer_entries()["bridge"]
    unnamed = sorted(
        part for part in parts_of(PACKAGE / "bridge") if not re.search(rf"\b{part}", bridge)
    )
    assert unnamed == [], f"bridge parts ARCHITECTURE.md does not name: {unnamed}"


def test_what_handlers_see_names_every_field_of_the_context() -> None:
    text = section("What handlers see")
    fields = [f.name for f in dataclasses.fields(BridgeContext)]
    fields += [f.name for f in dataclasses.fields(SessionState)]
    unnamed = [name for name in fields if not re.search(rf"`(\w+\.)*{name}`", text)]
    assert unnamed == [], f"context fields 'What handlers see' does not name: {unnamed}"
