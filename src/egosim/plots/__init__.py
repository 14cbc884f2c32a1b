"""Figures of egosim's maps and drives (matplotlib, Agg: no display needed).

Drawing only: every function takes maps, arrays and small dataclasses, never bags or
ROS messages, so the command line (`egosim map`, `egosim report`) and batch reports share
one look.

- `map_figure`: a LaneMap top-down (roads at their width, lane ids with their direction,
  lights, crosswalks, stop lines, sidewalks, a scale bar); `map_axes` + `draw_map` to add
  `draw_path` (a trajectory) and `draw_marks` (events at places) to the same picture.
- `series_figure`: time series as stacked `Panel`s of `Series`, with `TimeMark`s
  (events) drawn across every panel.
- `write_report` / `html_page`: a self-contained HTML page of `FigureBlock`s (PNG as
  data URIs, also written beside the page), `TableBlock`s and `TextBlock`s.
- `kind_color`, `light_color`: the colours of event kinds and light aspects.
"""

from .colors import kind_color, light_color
from .html import Block, FigureBlock, TableBlock, TextBlock, figure_png, html_page, write_report
from .map_figure import (
    DrawnLabels,
    PlaceMark,
    draw_map,
    draw_marks,
    draw_path,
    map_axes,
    map_figure,
    map_view,
    points_view,
)
from .series import Panel, Series, TimeMark, series_figure

__all__ = [
    "Block",
    "DrawnLabels",
    "FigureBlock",
    "Panel",
    "PlaceMark",
    "Series",
    "TableBlock",
    "TextBlock",
    "TimeMark",
    "draw_map",
    "draw_marks",
    "draw_path",
    "figure_png",
    "html_page",
    "kind_color",
    "light_color",
    "map_axes",
    "map_figure",
    "map_view",
    "points_view",
    "series_figure",
    "write_report",
]
