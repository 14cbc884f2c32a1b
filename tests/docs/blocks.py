"""The fenced code blocks of a Markdown file, and what the documentation test does with each.

A block's language says whether it is a command: `sh` (also `bash`, `shell`) runs in bash,
`python` in egosim's Python; others (`yaml`, untagged output) are not run. A marker on the
line before the block changes that:

    <!-- doc-test: skip: REASON -->    not run, and REASON says why (required)
    <!-- doc-test: simulator -->       starts the simulator: it runs in the background
                                       until the next such block or the end of the file,
                                       and the blocks after it run against it
    <!-- doc-test: prints -->          an output block: what the command block before it
                                       prints (each of its lines must be a line of that
                                       block's output)
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

SHELL_LANGUAGES = frozenset({"sh", "bash", "shell"})
PYTHON_LANGUAGES = frozenset({"python", "py"})
MARKER = re.compile(r"^<!--\s*doc-test:\s*(?P<kind>[a-z]+)\s*(?::\s*(?P<reason>.*?))?\s*-->$")
FENCE = re.compile(r"^(?P<fence>```+|~~~+)\s*(?P<language>[\w+-]*)")


class MarkerError(ValueError):
    """A doc-test marker that is malformed or stands before no block."""


@dataclass(frozen=True)
class Block:
    path: Path
    line: int
    """1-based line of the opening fence."""
    language: str
    text: str
    action: str
    """'run', 'simulator', 'skip', 'prints' (marked), or 'none' (not a command)."""
    reason: str = ""

    @property
    def where(self) -> str:
        return f"{self.path.name}:{self.line}"


def default_action(language: str) -> str:
    return "run" if language in SHELL_LANGUAGES | PYTHON_LANGUAGES else "none"


def parse_blocks(path: Path) -> list[Block]:
    """Every fenced block of `path` in order; MarkerError for a bad or stray marker."""
    lines = path.read_text(encoding="utf-8").splitlines()
    blocks: list[Block] = []
    pending: tuple[int, str, str] | None = None  # (line, kind, reason) of the last marker
    index = 0
    while index < len(lines):
        line = lines[index]
        if match := MARKER.match(line.strip()):
            kind, reason = match["kind"], match["reason"] or ""
            if kind not in ("skip", "simulator", "prints") or (kind == "skip") != bool(reason):
                raise MarkerError(f"{path.name}:{index + 1}: bad marker {line.strip()!r}")
            pending = (index + 1, kind, reason)
            index += 1
            continue
        fence = FENCE.match(line)
        if fence is None:
            if line.strip() and pending is not None:
                raise MarkerError(f"{path.name}:{pending[0]}: marker not followed by a block")
            index += 1
            continue
        end = index + 1
        while end < len(lines) and not lines[end].startswith(fence["fence"]):
            end += 1
        language = fence["language"].lower()
        action = default_action(language)
        reason = ""
        if pending is not None:
            action, reason = pending[1], pending[2]
            pending = None
        text = "\n".join(lines[index + 1 : end]) + "\n"
        blocks.append(Block(path, index + 1, language, text, action, reason))
        index = end + 1
    if pending is not None:
        raise MarkerError(f"{path.name}:{pending[0]}: marker not followed by a block")
    return blocks
