"""The HTML report: summary table, score histogram, and per failing case the trajectory
over the map and the infraction timeline (figures from egosim.plots)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from egosim.batch.documents import CaseResult, ResultsDocument, read_score_file
from egosim.batch.files import CASE_FILE
from egosim.batch.logs import tail_report
from egosim.evaluation import ScoreRecord
from egosim.maps import MapLoadError, load_map
from egosim.plots import (
    Block,
    FigureBlock,
    Panel,
    PlaceMark,
    Series,
    TableBlock,
    TextBlock,
    TimeMark,
    draw_map,
    draw_marks,
    draw_path,
    map_axes,
    points_view,
    series_figure,
    write_report,
)
from egosim.world.map import LaneMap

REPORT_FILE = "report.html"
MAX_DETAILED_CASES = 50
"""Failing cases drawn in full; the table lists every case whatever their number."""


def _fmt(value: float | None, digits: int = 3) -> str:
    if value is None:
        return "-"
    return f"{value:.{digits}g}" if isinstance(value, float) else str(value)


def summary_table(cases: list[CaseResult]) -> TableBlock:
    rows = []
    for case in cases:
        metrics = case.get("metrics") or {}
        rows.append(
            (
                case["name"],
                case["status"],
                _fmt(metrics.get("driving_score")),
                _fmt(metrics.get("route_completion")),
                _fmt(metrics.get("infractions")),
                case.get("end") or "-",
                case.get("reason") or "",
            )
        )
    columns = ("case", "status", "score", "route", "infractions", "end", "reason")
    return TableBlock("Cases", columns, rows)


def verdict_block(case: CaseResult) -> TextBlock:
    """A case's status and reason, with the end of the log that explains it."""
    lines = [case.get("reason") or "", *tail_report(case.get("log_tail"))]
    return TextBlock(f"{case['name']}: {case['status']}", "\n".join(lines))


def score_histogram(cases: list[CaseResult]) -> Figure:
    scores = [
        score
        for c in cases
        if (metrics := c.get("metrics")) is not None
        and (score := metrics.get("driving_score")) is not None
    ]
    figure = Figure(figsize=(6.0, 2.6), dpi=110)
    FigureCanvasAgg(figure)
    axes = figure.add_subplot()
    axes.hist(scores, bins=np.linspace(0.0, 1.0, 21).tolist(), color="#1f77b4", edgecolor="white")
    axes.set_xlabel("driving score", fontsize=8)
    axes.set_ylabel("cases", fontsize=8)
    axes.tick_params(labelsize=7)
    figure.tight_layout()
    return figure


def _case_figures(case: CaseResult, score: ScoreRecord, lane_map: LaneMap, key: str) -> list[Block]:
    trajectory = np.asarray(score["trajectory"], dtype=np.float64).reshape(-1, 4)
    infractions = score["infractions"]
    places = [(i["x"], i["y"]) for i in infractions]
    xy = np.vstack([trajectory[:, 1:3], np.asarray(places).reshape(-1, 2)])
    figure, axes = map_axes(points_view(xy) if len(xy) else lane_map.bounds(), max_px=700)
    draw_map(axes, lane_map)
    draw_path(axes, trajectory[:, 1:3], label="ego")
    draw_marks(
        axes, [PlaceMark(i["x"], i["y"], f"{i['time_s']:.1f} s", i["kind"]) for i in infractions]
    )
    axes.set_title(case["name"], fontsize=9)
    timeline = series_figure(
        [Panel("speed", "m/s", (Series("ego", trajectory[:, 0], trajectory[:, 3]),))],
        [TimeMark(i["time_s"], i["kind"], i["kind"]) for i in infractions],
        title="infraction timeline",
    )
    rows = [
        (f"{i['time_s']:.2f}", i["kind"], f"({i['x']:.1f}, {i['y']:.1f})", i["detail"])
        for i in infractions
    ]
    return [
        verdict_block(case),
        FigureBlock("Trajectory over the map", figure, f"{key}_map"),
        FigureBlock("Infraction timeline", timeline, f"{key}_timeline"),
        TableBlock("Infractions", ("t (s)", "kind", "where (m)", "detail"), rows),
    ]


def write_html_report(out_dir: Path, title: str, document: ResultsDocument) -> Path:
    cases = document["cases"]
    counts = document["summary"]
    text = ", ".join(f"{v} {k}" for k, v in counts.items())
    blocks: list[Block] = [TextBlock("Summary", text), summary_table(cases)]
    if any(c.get("metrics") for c in cases):
        blocks.append(FigureBlock("Driving scores", score_histogram(cases), "scores"))
    maps: dict[str, LaneMap | None] = {}
    failing = [
        (c, folder)
        for c in cases
        if c["status"] in ("failed", "error") and (folder := c.get("folder"))
    ]
    for k, (case, folder) in enumerate(failing[:MAX_DETAILED_CASES]):
        drive = read_score_file(out_dir / folder)
        score = None if drive is None else drive["score"]
        if score is None:
            blocks.append(verdict_block(case))
            continue
        map_name = _map_name(out_dir / folder)
        if map_name not in maps:
            try:
                maps[map_name] = load_map(map_name)
            except MapLoadError:
                maps[map_name] = None
        lane_map = maps[map_name]
        if lane_map is None:
            blocks.extend(
                (verdict_block(case), TextBlock(case["name"], f"map {map_name} not found"))
            )
            continue
        blocks.extend(_case_figures(case, score, lane_map, f"case{k}"))
    if len(failing) > MAX_DETAILED_CASES:
        blocks.append(TextBlock("More failures", f"{len(failing) - MAX_DETAILED_CASES} not drawn"))
    path = out_dir / REPORT_FILE
    write_report(path, title, blocks)
    return path


def _map_name(folder: Path) -> str:
    case = json.loads((folder / CASE_FILE).read_text(encoding="utf-8"))
    return str(case["map"])
