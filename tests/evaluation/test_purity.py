"""egosim.evaluation is pure: it imports nothing above the world and nothing that does I/O."""

from __future__ import annotations

import ast
from pathlib import Path

import egosim.evaluation

PACKAGE = Path(egosim.evaluation.__file__).parent
ALLOWED_EGOSIM = ("egosim.evaluation", "egosim.world")
FORBIDDEN_STDLIB = {"os", "io", "socket", "subprocess", "threading", "pathlib", "time", "logging"}


def imported_modules(path: Path) -> set[str]:
    names = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            names.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module is not None and node.level == 0:
            names.add(node.module)
    return names


def test_evaluation_imports_only_the_world_and_pure_libraries() -> None:
    files = sorted(PACKAGE.glob("*.py"))
    assert len(files) >= 5
    for path in files:
        for name in imported_modules(path):
            root = name.split(".")[0]
            if root == "egosim":
                assert name.startswith(ALLOWED_EGOSIM), f"{path.name} imports {name}"
            assert root not in FORBIDDEN_STDLIB, f"{path.name} imports {name}"
