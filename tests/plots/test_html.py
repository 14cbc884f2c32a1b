"""The report page stands alone: figures embedded, PNGs beside it, text escaped."""

from __future__ import annotations

import base64
import io
import re
from pathlib import Path

import pytest
from PIL import Image

from egosim.plots import (
    FigureBlock,
    Panel,
    Series,
    TableBlock,
    TextBlock,
    series_figure,
    write_report,
)


def _figure():
    return series_figure([Panel("speed", "m/s", (Series("speed", [0, 1, 2], [0, 1, 4]),))])


def test_page_embeds_each_png_it_writes_beside_it(tmp_path: Path) -> None:
    page = tmp_path / "drive.html"
    written = write_report(
        page,
        "Drive <1>",
        [
            TextBlock("Summary", "3 collisions & 1 red light"),
            FigureBlock("Speed", _figure(), "speed", caption="m/s over time"),
            TableBlock("Events", ("t (s)", "what"), [(1.25, "collision"), (float("nan"), "x")]),
        ],
    )
    assert written == [page, tmp_path / "drive_speed.png"]
    text = page.read_text()
    assert "<title>Drive &lt;1&gt;</title>" in text
    assert "3 collisions &amp; 1 red light" in text
    assert "<td>1.25</td><td>collision</td>" in text and "<td>-</td>" in text
    (data,) = re.findall(r'src="data:image/png;base64,([^"]+)"', text)
    png = base64.b64decode(data)
    assert png == (tmp_path / "drive_speed.png").read_bytes()
    Image.open(io.BytesIO(png)).verify()
    # Nothing else is fetched: no other src or href.
    assert re.findall(r'(?:src|href)="(?!data:)', text) == []


def test_figure_names_must_be_file_safe_and_unique(tmp_path: Path) -> None:
    figure = _figure()
    with pytest.raises(ValueError, match="repeat"):
        write_report(tmp_path / "a.html", "a", [FigureBlock("a", figure, "x")] * 2)
    with pytest.raises(ValueError, match="letters"):
        write_report(tmp_path / "a.html", "a", [FigureBlock("a", figure, "../x")])
