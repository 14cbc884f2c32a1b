"""Time series figures: stacked panels on one time axis, with events marked across them.

panels = [
    Panel("speed", "m/s", (Series("speed", t, v),)),
    Panel("pedals", "0..1", (Series("accel", t, a), Series("brake", t, b))),
]
figure = series_figure(panels, marks=[TimeMark(12.5, "hit NPC 3", "collision")])
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

from . import colors

DEFAULT_WIDTH_IN = 10.0
PANEL_HEIGHT_IN = 1.7
DEFAULT_DPI = 110


@dataclass(frozen=True, eq=False)
class Series:
    """One line: `values` at `times_s` (equal lengths; NaN leaves a gap)."""

    label: str
    times_s: npt.ArrayLike
    values: npt.ArrayLike


@dataclass(frozen=True)
class Panel:
    """One plot of the stack: its series share a y axis in `unit`."""

    title: str
    unit: str
    series: tuple[Series, ...]


@dataclass(frozen=True)
class TimeMark:
    """Something that happened at a time: a vertical line in its kind's colour."""

    time_s: float
    label: str
    kind: str


def series_figure(
    panels: Sequence[Panel],
    marks: Sequence[TimeMark] = (),
    *,
    title: str | None = None,
    width_in: float = DEFAULT_WIDTH_IN,
    panel_height_in: float = PANEL_HEIGHT_IN,
    dpi: int = DEFAULT_DPI,
) -> Figure:
    """The panels stacked top to bottom on one time axis (s); each mark is a line through
    every panel, labelled in the top one, with one legend entry per kind."""
    if not panels:
        raise ValueError("series_figure needs at least one panel")
    figure = Figure(figsize=(width_in, panel_height_in * len(panels) + 0.6), dpi=dpi)
    FigureCanvasAgg(figure)
    axes_list = figure.subplots(len(panels), 1, sharex=True, squeeze=False)[:, 0]
    for axes, panel in zip(axes_list, panels, strict=True):
        for series in panel.series:
            times = np.asarray(series.times_s, dtype=np.float64)
            values = np.asarray(series.values, dtype=np.float64)
            if times.shape != values.shape:
                raise ValueError(
                    f"series {series.label!r}: {times.shape} times but {values.shape} values"
                )
            axes.plot(times, values, linewidth=1.0, label=series.label)
        axes.set_ylabel(f"{panel.title}\n({panel.unit})", fontsize=8)
        axes.tick_params(labelsize=7)
        axes.grid(True, linewidth=0.4, alpha=0.6)
        if len(panel.series) > 1:
            axes.legend(fontsize=7, loc="upper right")
        for mark in marks:
            axes.axvline(mark.time_s, color=colors.kind_color(mark.kind), linewidth=1.0, alpha=0.9)
    top = axes_list[0]
    for mark in marks:
        top.annotate(
            mark.label, (mark.time_s, 1.0), xycoords=("data", "axes fraction"),
            xytext=(2, 2), textcoords="offset points", fontsize=6, rotation=30,
            color=colors.kind_color(mark.kind),
        )  # fmt: skip
    kinds = sorted({mark.kind for mark in marks})
    if kinds:
        figure.legend(
            [Line2D([], [], color=colors.kind_color(kind)) for kind in kinds],
            kinds,
            loc="lower right",
            fontsize=7,
            ncols=len(kinds),
            frameon=False,
        )
    axes_list[-1].set_xlabel("time (s)", fontsize=8)
    if title:
        figure.suptitle(title, fontsize=10)
    figure.tight_layout(rect=(0, 0.03 if kinds else 0, 1, 0.97 if marks else 1))
    return figure


__all__ = ["Panel", "Series", "TimeMark", "series_figure"]
