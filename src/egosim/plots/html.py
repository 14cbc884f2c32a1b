"""A self-contained HTML page from figures, tables and text.

    blocks = [TextBlock("Run", "3 collisions"), FigureBlock("Speed", figure, "speed"),
              TableBlock("Events", ("t (s)", "what"), [(1.5, "collision")])]
    written = write_report(Path("out/report.html"), "Drive report", blocks)

Every figure is rendered to PNG once: embedded in the page as a data URI (the page needs
no other file and no network) and also written beside it as `<page stem>_<name>.png`.
"""

from __future__ import annotations

import base64
import html
import io
import math
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

_STYLE = """
body { font-family: system-ui, sans-serif; margin: 1.5em auto; max-width: 1100px;
       color: #222; padding: 0 1em; }
h1 { font-size: 1.5em; } h2 { font-size: 1.15em; margin-top: 1.6em; }
img { max-width: 100%; height: auto; border: 1px solid #ddd; }
table { border-collapse: collapse; font-size: 0.9em; }
th, td { border: 1px solid #ccc; padding: 0.25em 0.6em; text-align: left; }
th { background: #f0f0f0; } p.caption { color: #555; font-size: 0.9em; }
pre { white-space: pre-wrap; }
"""


@dataclass(frozen=True)
class FigureBlock:
    """A figure under a heading; `name` names its PNG file (letters, digits, `_`, `-`)."""

    title: str
    figure: Figure
    name: str
    caption: str = ""


@dataclass(frozen=True)
class TableBlock:
    title: str
    columns: tuple[str, ...]
    rows: Sequence[Sequence[object]]


@dataclass(frozen=True)
class TextBlock:
    """A paragraph of plain text (line breaks kept)."""

    title: str
    text: str


Block = FigureBlock | TableBlock | TextBlock


def figure_png(figure: Figure) -> bytes:
    """The figure as PNG bytes, at its own dpi."""
    canvas = figure.canvas
    if not isinstance(canvas, FigureCanvasAgg):
        canvas = FigureCanvasAgg(figure)
    buffer = io.BytesIO()
    figure.savefig(buffer, format="png")
    return buffer.getvalue()


def html_page(title: str, blocks: Sequence[Block], pngs: dict[str, bytes] | None = None) -> str:
    """The page as text; figures come from `pngs` (name -> PNG) when given, else are
    rendered here."""
    parts = [
        "<!DOCTYPE html>",
        '<html lang="en"><head><meta charset="utf-8">',
        f"<title>{html.escape(title)}</title><style>{_STYLE}</style></head><body>",
        f"<h1>{html.escape(title)}</h1>",
    ]
    for block in blocks:
        parts.append(f"<h2>{html.escape(block.title)}</h2>")
        if isinstance(block, FigureBlock):
            png = pngs[block.name] if pngs is not None else figure_png(block.figure)
            data = base64.b64encode(png).decode("ascii")
            parts.append(
                f'<img alt="{html.escape(block.title)}" src="data:image/png;base64,{data}">'
            )
            if block.caption:
                parts.append(f'<p class="caption">{html.escape(block.caption)}</p>')
        elif isinstance(block, TableBlock):
            parts.append(_table(block))
        else:
            parts.append(f"<pre>{html.escape(block.text)}</pre>")
    parts.append("</body></html>")
    return "\n".join(parts) + "\n"


def write_report(path: Path, title: str, blocks: Sequence[Block]) -> list[Path]:
    """Write the page at `path` and each figure's PNG beside it; returns the files written
    (the page first)."""
    names = [b.name for b in blocks if isinstance(b, FigureBlock)]
    if len(set(names)) != len(names):
        raise ValueError(f"figure names repeat: {names}")
    bad = [n for n in names if not n or not all(c.isalnum() or c in "_-" for c in n)]
    if bad:
        raise ValueError(f"figure names must be letters, digits, '_' or '-': {bad}")
    pngs = {b.name: figure_png(b.figure) for b in blocks if isinstance(b, FigureBlock)}
    path.write_text(html_page(title, blocks, pngs), encoding="utf-8")
    written = [path]
    for name, png in pngs.items():
        png_path = path.with_name(f"{path.stem}_{name}.png")
        png_path.write_bytes(png)
        written.append(png_path)
    return written


def _table(block: TableBlock) -> str:
    head = "".join(f"<th>{html.escape(c)}</th>" for c in block.columns)
    body = "".join(
        "<tr>" + "".join(f"<td>{html.escape(_cell(v))}</td>" for v in row) + "</tr>"
        for row in block.rows
    )
    return f"<table><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>"


def _cell(value: object) -> str:
    if isinstance(value, float):
        return "-" if math.isnan(value) else f"{value:.3f}".rstrip("0").rstrip(".")
    return str(value)


__all__ = [
    "Block",
    "FigureBlock",
    "TableBlock",
    "TextBlock",
    "figure_png",
    "html_page",
    "write_report",
]
