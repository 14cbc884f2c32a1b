"""The Python blocks of the documentation run as written (from the repository's root)."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
import yaml

REPOSITORY = Path(__file__).parents[1]
DOCS_WITH_PYTHON = ("docs/scenarios.md", "docs/maps.md")
PYTHON_BLOCK = re.compile(r"^```python\n(.*?)^```", re.MULTILINE | re.DOTALL)


def python_blocks(doc: str) -> list[str]:
    return PYTHON_BLOCK.findall((REPOSITORY / doc).read_text(encoding="utf-8"))


@pytest.mark.parametrize("doc", DOCS_WITH_PYTHON)
def test_python_blocks_run_as_written(
    doc: str, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    blocks = python_blocks(doc)
    assert blocks, f"{doc} has no Python block"
    monkeypatch.chdir(REPOSITORY)
    for number, block in enumerate(blocks, start=1):
        # Each block stands alone: a reader pastes one at a time.
        exec(compile(block, f"{doc} block {number}", "exec"), {"__name__": "__doc_block__"})
    printed = capsys.readouterr().out
    for expected in re.findall(r"^which prints `(.*)`", (REPOSITORY / doc).read_text(), re.M):
        assert expected in printed


def test_the_scenario_tutorial_prints_what_it_says() -> None:
    text = (REPOSITORY / "docs" / "scenarios.md").read_text(encoding="utf-8")
    assert text.index("## Tutorial") < text.index("## Units")
    assert "which prints `t = 2.00 s: the NPC cuts in" in text


def test_the_tutorial_builds_the_gallery_file() -> None:
    text = (REPOSITORY / "docs" / "scenarios.md").read_text(encoding="utf-8")
    tutorial = text[text.index("## Tutorial") : text.index("## Loading in code")]
    steps = re.findall(r"^```yaml\n(.*?)^```", tutorial, re.MULTILINE | re.DOTALL)
    assert len(steps) == 3
    built = yaml.safe_load("".join(steps))
    gallery = yaml.safe_load((REPOSITORY / "examples" / "scenarios" / "cut_in.yaml").read_text())
    assert built == gallery
