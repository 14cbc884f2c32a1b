"""The documentation test reads blocks and markers as tests/docs/blocks.py says."""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.docs.blocks import MarkerError, parse_blocks

DOCUMENT = """\
# Title

<!-- doc-test: simulator -->
```sh
egosim run
```

```
egosim: ready
```

<!-- doc-test: skip: needs a map of your own -->

```bash
egosim run --map ~/maps/kcity
```

```python
print("hello")
```

```yaml
map: town
```
"""


def test_blocks_get_their_language_action_and_reason(tmp_path: Path) -> None:
    path = tmp_path / "doc.md"
    path.write_text(DOCUMENT)
    blocks = parse_blocks(path)
    assert [(b.line, b.language, b.action) for b in blocks] == [
        (4, "sh", "simulator"),
        (8, "", "none"),
        (14, "bash", "skip"),
        (18, "python", "run"),
        (22, "yaml", "none"),
    ]
    assert blocks[2].reason == "needs a map of your own"
    assert blocks[0].text == "egosim run\n"


@pytest.mark.parametrize(
    "marker",
    [
        "<!-- doc-test: skip -->",  # no reason
        "<!-- doc-test: later -->",  # no such marker
    ],
)
def test_a_malformed_marker_is_refused(tmp_path: Path, marker: str) -> None:
    path = tmp_path / "doc.md"
    path.write_text(f"{marker}\n```sh\ntrue\n```\n")
    with pytest.raises(MarkerError, match="bad marker"):
        parse_blocks(path)


def test_a_marker_before_prose_is_refused(tmp_path: Path) -> None:
    path = tmp_path / "doc.md"
    path.write_text("<!-- doc-test: skip: slow -->\nSome prose.\n```sh\ntrue\n```\n")
    with pytest.raises(MarkerError, match="not followed by a block"):
        parse_blocks(path)


def test_an_output_block_marked_prints(tmp_path: Path) -> None:
    path = tmp_path / "doc.md"
    path.write_text("```sh\necho hi\n```\n\n<!-- doc-test: prints -->\n```\nhi\n```\n")
    run, printed = parse_blocks(path)
    assert (run.action, printed.action, printed.text) == ("run", "prints", "hi\n")
