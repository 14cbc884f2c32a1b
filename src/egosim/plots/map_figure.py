"""A LaneMap drawn top-down: roads, lane ids, lights, crosswalks, stop lines, scale bar.

    figure, axes = map_axes(map_view(lane_map))
    drawn = draw_map(axes, lane_map)            # which ids got a label
    draw_path(axes, xy)                         # a trajectory, (N, 2) metres
    draw_marks(axes, [PlaceMark(x, y, "collision", "collision")])

The figure is sized so the map keeps its proportions (1 m is as long across as up) and its
longer side spans `max_px` pixels; labels that would overlap one drawn earlier are left
out rather than drawn on top of each other (`DrawnLabels` tells which were drawn).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt
from matplotlib.artist import Artist
from matplotlib.axes import Axes
from matplotlib.backend_bases import RendererBase
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.collections import LineCollection, PolyCollection
from matplotlib.figure import Figure
from matplotlib.text import Text
from mpl_toolkits.axes_grid1.anchored_artists import AnchoredSizeBar

from egosim.world.map import Lane, LaneMap

from . import colors

DEFAULT_DPI = 150
DEFAULT_MAX_PX = 2400
# Empty border around what is shown, as a fraction of its larger side (at least VIEW_PAD_M).
VIEW_PAD_FRACTION = 0.03
VIEW_PAD_M = 5.0
# A view is never flatter than this (a 1 km straight road still gets some height).
MIN_VIEW_ASPECT = 0.15
# Room for the axes' tick labels around the map, inches (left, bottom, right, top).
MARGINS_IN = (0.75, 0.5, 0.2, 0.35)
# Lane labels are as tall as LABEL_HEIGHT_OF_LANE of a lane's width, within these sizes.
LABEL_HEIGHT_OF_LANE = 0.7
LABEL_FONT_PT = (6.0, 11.0)
LIGHT_FONT_PT = 5.5
# Where along a lane its label may go (fractions of its length), tried in this order.
LABEL_STATIONS = (0.5, 0.3, 0.7, 0.15, 0.85)
LIGHT_LABEL_OFFSETS_PT = ((5.0, 3.0), (5.0, -9.0), (-30.0, 3.0), (-30.0, -9.0))

Bounds = tuple[float, float, float, float]


@dataclass(frozen=True)
class PlaceMark:
    """Something that happened at a place: drawn as a cross in its kind's colour."""

    x: float
    y: float
    label: str
    kind: str


@dataclass(frozen=True)
class DrawnLabels:
    """The ids `draw_map` wrote on the picture (the rest had no room or were out of view)."""

    lanes: tuple[str, ...]
    lights: tuple[str, ...]


def map_view(lane_map: LaneMap) -> Bounds:
    """(xmin, ymin, xmax, ymax) showing the whole map."""
    return lane_map.bounds()


def points_view(xy: npt.ArrayLike, margin_m: float = 30.0) -> Bounds:
    """(xmin, ymin, xmax, ymax) around (N, 2) points with `margin_m` on every side."""
    points = np.asarray(xy, dtype=np.float64).reshape(-1, 2)
    lo, hi = points.min(axis=0) - margin_m, points.max(axis=0) + margin_m
    return float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1])


def map_axes(
    view: Bounds, *, max_px: int = DEFAULT_MAX_PX, dpi: int = DEFAULT_DPI
) -> tuple[Figure, Axes]:
    """A figure whose axes show `view` at equal scale on both axes, in metres."""
    xmin, ymin, xmax, ymax = _padded(view)
    width, height = xmax - xmin, ymax - ymin
    px_per_m = max_px / max(width, height)
    left, bottom, right, top = MARGINS_IN
    plot_w, plot_h = width * px_per_m / dpi, height * px_per_m / dpi
    fig_w, fig_h = plot_w + left + right, plot_h + bottom + top
    figure = Figure(figsize=(fig_w, fig_h), dpi=dpi)
    FigureCanvasAgg(figure)
    axes = figure.add_axes((left / fig_w, bottom / fig_h, plot_w / fig_w, plot_h / fig_h))
    axes.set_xlim(xmin, xmax)
    axes.set_ylim(ymin, ymax)
    axes.set_aspect("equal", adjustable="box")
    axes.set_facecolor("#f4f4ef")
    axes.tick_params(labelsize=7)
    axes.set_xlabel("x east (m)", fontsize=7, labelpad=1)
    axes.set_ylabel("y north (m)", fontsize=7, labelpad=1)
    axes.grid(True, color="white", linewidth=0.6)
    axes.set_axisbelow(True)
    return figure, axes


def draw_map(
    axes: Axes,
    lane_map: LaneMap,
    *,
    lane_ids: bool = True,
    junction_lane_ids: bool = False,
    light_ids: bool = True,
    crosswalks: bool = True,
    stop_lines: bool = True,
    sidewalks: bool = True,
    scale_bar: bool = True,
    light_aspects: Mapping[str, int] | None = None,
) -> DrawnLabels:
    """Draw `lane_map` on `axes` (set the axes' limits first: labels are placed for them).

    Lanes are drawn at their width with their centre line; `light_aspects` (light id ->
    protocol aspect bits) colours the lights, unknown ones grey. Junction connectors are
    labelled only with `junction_lane_ids`.
    """
    figure = axes.get_figure()
    assert isinstance(figure, Figure)
    px_per_m = axes.get_window_extent().width / abs(np.subtract(*axes.get_xlim()))
    pt_per_m = px_per_m * 72.0 / figure.dpi
    lanes = list(lane_map.lanes.values())
    for junction in (True, False):  # junction connectors beneath the roads
        chosen = [lane for lane in lanes if lane.is_junction == junction]
        if not chosen:
            continue
        axes.add_collection(
            LineCollection(
                [lane.centerline[:, :2] for lane in chosen],
                linewidths=[float(np.mean(lane.widths)) * pt_per_m for lane in chosen],
                colors=colors.JUNCTION_ROAD if junction else colors.ROAD,
                capstyle="butt",
                zorder=1,
            )
        )
    axes.add_collection(
        LineCollection(
            [lane.centerline[:, :2] for lane in lanes],
            linewidths=0.3,
            colors=colors.CENTRE_LINE,
            zorder=2,
        )
    )
    if sidewalks and lane_map.sidewalks:
        axes.add_collection(
            LineCollection(
                [s.points[:, :2] for s in lane_map.sidewalks.values()],
                linewidths=max(1.0, 2.0 * pt_per_m),
                colors=colors.SIDEWALK,
                zorder=1,
            )
        )
    if crosswalks and lane_map.crosswalks:
        axes.add_collection(
            PolyCollection(
                [_crosswalk_outline(c.start, c.end, c.width) for c in lane_map.crosswalks.values()],
                facecolors=colors.CROSSWALK,
                edgecolors=colors.CROSSWALK_EDGE,
                linewidths=0.4,
                hatch="||||",
                zorder=3,
            )
        )
    if stop_lines:
        segments = [_stop_line(lane_map, lane) for lane in lanes if lane.stop_line_s is not None]
        if segments:
            axes.add_collection(
                LineCollection(segments, linewidths=1.0, colors=colors.STOP_LINE, zorder=4)
            )
    placer = _LabelPlacer(axes)
    if scale_bar:
        placer.reserve(_draw_scale_bar(axes))
    drawn_lights = _draw_lights(axes, lane_map, light_aspects or {}, placer if light_ids else None)
    font_pt = LABEL_HEIGHT_OF_LANE * float(np.median([np.mean(lane.widths) for lane in lanes]))
    font_pt = min(max(font_pt * pt_per_m, LABEL_FONT_PT[0]), LABEL_FONT_PT[1])
    drawn_lanes = (
        _label_lanes(axes, lane_map, placer, junction_lane_ids, font_pt) if lane_ids else ()
    )
    return DrawnLabels(lanes=drawn_lanes, lights=drawn_lights)


def draw_path(
    axes: Axes,
    xy: npt.ArrayLike,
    *,
    color: str = colors.PATH,
    label: str | None = None,
    linewidth: float = 1.6,
) -> None:
    """An (N, 2) path in metres, with a circle at its start and a square at its end."""
    points = np.asarray(xy, dtype=np.float64).reshape(-1, 2)
    if not len(points):
        return
    axes.plot(points[:, 0], points[:, 1], color=color, linewidth=linewidth, label=label, zorder=6)
    axes.plot(*points[0], marker="o", color=color, markersize=5, zorder=7)
    axes.plot(*points[-1], marker="s", color=color, markersize=5, zorder=7)


def draw_marks(axes: Axes, marks: Iterable[PlaceMark]) -> None:
    """Crosses at each mark's place, coloured by kind, with its label beside."""
    for mark in marks:
        color = colors.kind_color(mark.kind)
        axes.plot(
            mark.x, mark.y, marker="X", color=color, markersize=8, markeredgecolor="black",
            markeredgewidth=0.5, zorder=8,
        )  # fmt: skip
        axes.annotate(
            mark.label,
            (mark.x, mark.y),
            xytext=(6, 4),
            textcoords="offset points",
            fontsize=7,
            color=color,
            zorder=8,
        )


def map_figure(
    lane_map: LaneMap,
    *,
    view: Bounds | None = None,
    max_px: int = DEFAULT_MAX_PX,
    dpi: int = DEFAULT_DPI,
    title: str | None = None,
    **layers: bool,
) -> tuple[Figure, DrawnLabels]:
    """`map_axes` + `draw_map` in one call; `layers` are draw_map's switches."""
    figure, axes = map_axes(view or map_view(lane_map), max_px=max_px, dpi=dpi)
    drawn = draw_map(axes, lane_map, **layers)
    axes.set_title(title if title is not None else f"map {lane_map.name}", fontsize=9)
    return figure, drawn


def nice_length(span: float) -> float:
    """The 1, 2 or 5 x 10^k length nearest below a fifth of `span` (a scale bar's length)."""
    target = span / 5.0
    power = 10.0 ** math.floor(math.log10(target))
    return max(m * power for m in (1.0, 2.0, 5.0) if m * power <= target)


def _padded(view: Bounds) -> Bounds:
    xmin, ymin, xmax, ymax = view
    pad = max(VIEW_PAD_M, VIEW_PAD_FRACTION * max(xmax - xmin, ymax - ymin))
    xmin, ymin, xmax, ymax = xmin - pad, ymin - pad, xmax + pad, ymax + pad
    width, height = xmax - xmin, ymax - ymin
    if height < MIN_VIEW_ASPECT * width:
        grow = (MIN_VIEW_ASPECT * width - height) / 2.0
        ymin, ymax = ymin - grow, ymax + grow
    elif width < MIN_VIEW_ASPECT * height:
        grow = (MIN_VIEW_ASPECT * height - width) / 2.0
        xmin, xmax = xmin - grow, xmax + grow
    return xmin, ymin, xmax, ymax


def _crosswalk_outline(
    start: tuple[float, float], end: tuple[float, float], width: float
) -> npt.NDArray[np.float64]:
    a, b = np.asarray(start, dtype=np.float64), np.asarray(end, dtype=np.float64)
    along = (b - a) / max(float(np.hypot(*(b - a))), 1e-9)
    side = np.array((-along[1], along[0])) * width / 2.0
    return np.array((a + side, b + side, b - side, a - side))


def _stop_line(lane_map: LaneMap, lane: Lane) -> npt.NDArray[np.float64]:
    assert lane.stop_line_s is not None
    x, y, _, heading = lane_map.pose_at(lane.id, lane.stop_line_s)
    half = float(np.interp(lane.stop_line_s, lane.stations, lane.widths)) / 2.0
    centre = np.array((x, y))
    side = np.array((-math.sin(heading), math.cos(heading))) * half
    return np.array((centre + side, centre - side))


class _LabelPlacer:
    """Adds texts unless they would overlap a text added before (display-pixel boxes)."""

    def __init__(self, axes: Axes) -> None:
        self.axes = axes
        self.renderer = _renderer(axes)
        self.frame = axes.get_window_extent(self.renderer)
        self.boxes = np.zeros((0, 4))

    def inside(self, x: float, y: float) -> bool:
        px, py = self.axes.transData.transform((x, y))
        return bool(self.frame.contains(px, py))

    def reserve(self, artist: Artist) -> None:
        """Keep labels off `artist`."""
        box = artist.get_window_extent(self.renderer)
        self.boxes = np.vstack((self.boxes, (box.x0, box.y0, box.x1, box.y1)))

    def try_add(self, text: Text) -> bool:
        box = text.get_window_extent(self.renderer)
        b = np.array((box.x0, box.y0, box.x1, box.y1))
        fits = (
            b[0] >= self.frame.x0
            and b[2] <= self.frame.x1
            and b[1] >= self.frame.y0
            and b[3] <= self.frame.y1
        )
        clash = np.any(
            (self.boxes[:, 0] < b[2])
            & (b[0] < self.boxes[:, 2])
            & (self.boxes[:, 1] < b[3])
            & (b[1] < self.boxes[:, 3])
        )
        if not fits or clash:
            text.remove()
            return False
        self.boxes = np.vstack((self.boxes, b))
        return True


def _renderer(axes: Axes) -> RendererBase:
    figure = axes.get_figure()
    assert isinstance(figure, Figure)
    canvas = figure.canvas
    if not isinstance(canvas, FigureCanvasAgg):
        canvas = FigureCanvasAgg(figure)
    return canvas.get_renderer()


def _lane_label(lane_map: LaneMap, lane: Lane, fraction: float) -> tuple[float, float, float, str]:
    """(x, y, text rotation deg, text) at `fraction` of the lane, readable left to right,
    with an arrow pointing the lane's way."""
    x, y, _, heading = lane_map.pose_at(lane.id, fraction * lane.length)
    degrees = math.degrees(heading)
    if -90.0 < degrees <= 90.0:
        return x, y, degrees, f"{lane.id} →"
    return x, y, degrees + (180.0 if degrees <= -90.0 else -180.0), f"← {lane.id}"


def _label_lanes(
    axes: Axes, lane_map: LaneMap, placer: _LabelPlacer, junction_lanes: bool, font_pt: float
) -> tuple[str, ...]:
    drawn: list[str] = []
    for lane in lane_map.lanes.values():
        if lane.is_junction and not junction_lanes:
            continue
        for fraction in LABEL_STATIONS:
            x, y, rotation, label = _lane_label(lane_map, lane, fraction)
            if not placer.inside(x, y):
                continue
            text = axes.text(
                x, y, label, fontsize=font_pt, color=colors.LANE_LABEL, rotation=rotation,
                rotation_mode="anchor", ha="center", va="center", zorder=9,
            )  # fmt: skip
            if placer.try_add(text):
                drawn.append(lane.id)
                break
    return tuple(drawn)


def _draw_lights(
    axes: Axes,
    lane_map: LaneMap,
    aspects: Mapping[str, int],
    placer: _LabelPlacer | None,
) -> tuple[str, ...]:
    lights = list(lane_map.traffic_lights.values())
    if not lights:
        return ()
    axes.scatter(
        [light.position[0] for light in lights],
        [light.position[1] for light in lights],
        s=14,
        c=[colors.light_color(aspects.get(light.id)) for light in lights],
        edgecolors="black",
        linewidths=0.5,
        zorder=10,
    )
    if placer is None:
        return ()
    drawn: list[str] = []
    for light in lights:
        x, y = light.position[0], light.position[1]
        if not placer.inside(x, y):
            continue
        for offset in LIGHT_LABEL_OFFSETS_PT:
            text = axes.annotate(
                light.id, (x, y), xytext=offset, textcoords="offset points",
                fontsize=LIGHT_FONT_PT, color=colors.LIGHT_LABEL, zorder=10,
            )  # fmt: skip
            if placer.try_add(text):
                drawn.append(light.id)
                break
    return tuple(drawn)


def _draw_scale_bar(axes: Axes) -> Artist:
    length = nice_length(abs(np.subtract(*axes.get_xlim())))
    thickness = min(length, abs(np.subtract(*axes.get_ylim()))) / 60.0
    return axes.add_artist(
        AnchoredSizeBar(
            axes.transData,
            length,
            f"{length:g} m",
            "lower right",
            pad=0.6,
            borderpad=0.8,
            sep=3,
            size_vertical=thickness,
            frameon=True,
            fontproperties={"size": 8},
        )
    )


__all__ = [
    "DEFAULT_DPI",
    "DEFAULT_MAX_PX",
    "DrawnLabels",
    "PlaceMark",
    "draw_map",
    "draw_marks",
    "draw_path",
    "map_axes",
    "map_figure",
    "map_view",
    "nice_length",
    "points_view",
]
