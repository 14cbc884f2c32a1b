"""`egosim map`: what a map holds, its ids with their positions, and its picture."""

from __future__ import annotations

import argparse
import math
import sys
from collections.abc import Sequence
from pathlib import Path

from ..app.exit_codes import EXIT_BAD_INPUT
from ..maps import MapLoadError, read_map
from ..world.map import DEFAULT_MAP_NAME, GeoReference, LaneMap


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.description = (
        "What a map holds (size, georeference, counts), its lane, light and "
        "crosswalk ids with their positions, and a top-down picture with lane and light ids "
        "and a scale bar. Positions are in the map frame: metres, x east, y north; headings "
        "in degrees counter-clockwise from east, as scenario files write them."
    )
    parser.add_argument(
        "map",
        nargs="?",
        default=DEFAULT_MAP_NAME,
        metavar="NAME|PATH",
        help=f"a built-in map name, an MGeo folder or an OpenDRIVE .xodr file "
        f"(default {DEFAULT_MAP_NAME})",
    )
    parser.add_argument("--png", type=Path, metavar="FILE", help="draw the map into this PNG")
    parser.add_argument(
        "--size",
        type=int,
        default=2400,
        metavar="PX",
        help="the picture's longer side in pixels (default 2400)",
    )
    parser.add_argument(
        "--junction-ids",
        action="store_true",
        help="label junction connectors too in the picture (crowded on large maps)",
    )
    parser.add_argument("--lanes", action="store_true", help="list every lane")
    parser.add_argument("--lights", action="store_true", help="list every traffic light")
    parser.add_argument("--crosswalks", action="store_true", help="list every crosswalk")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    try:
        loaded = read_map(args.map)
    except MapLoadError as error:
        print(f"egosim map: {error}", file=sys.stderr)
        return EXIT_BAD_INPUT
    if args.size < 200:
        print("egosim map: --size must be at least 200 px", file=sys.stderr)
        return EXIT_BAD_INPUT
    lane_map = loaded.lane_map
    print("\n".join(summary_lines(lane_map)))
    for note in loaded.notes:
        print(f"note: {note}")
    if args.lanes:
        _print_table(lane_rows(lane_map), "lanes")
    if args.lights:
        _print_table(light_rows(lane_map), "traffic lights")
    if args.crosswalks:
        _print_table(crosswalk_rows(lane_map), "crosswalks")
    if args.png is not None:
        return _write_png(lane_map, args.png, args.size, args.junction_ids)
    return 0


def summary_lines(lane_map: LaneMap) -> list[str]:
    """What the map holds, one fact a line."""
    xmin, ymin, xmax, ymax = lane_map.bounds()
    lanes = list(lane_map.lanes.values())
    connectors = sum(lane.is_junction for lane in lanes)
    with_stop_line = sum(lane.stop_line_s is not None for lane in lanes)
    return [
        f"map: {lane_map.name}",
        f"size: {xmax - xmin:.1f} m x {ymax - ymin:.1f} m "
        f"(x {xmin:.1f} .. {xmax:.1f}, y {ymin:.1f} .. {ymax:.1f})",
        f"georeference: {_georeference(lane_map.georef)}",
        f"lanes: {len(lanes)} ({len(lanes) - connectors} road lanes, {connectors} junction "
        f"connectors, {with_stop_line} with a stop line), "
        f"{sum(lane.length for lane in lanes) / 1000:.1f} km",
        f"intersections: {len(lane_map.intersections)} signalised",
        f"traffic lights: {len(lane_map.traffic_lights)}",
        f"crosswalks: {len(lane_map.crosswalks)}",
        f"sidewalks: {len(lane_map.sidewalks)}",
    ]


def lane_rows(lane_map: LaneMap) -> list[tuple[str, ...]]:
    """Header and one row per lane: its start pose, length, limit and links."""
    rows: list[tuple[str, ...]] = [
        ("lane", "x", "y", "heading_deg", "length_m", "limit_mps", "junction", "stop_s",
         "light", "successors"),
    ]  # fmt: skip
    for lane in lane_map.lanes.values():
        x, y, _, heading = lane_map.pose_at(lane.id, 0.0)
        rows.append(
            (
                lane.id,
                f"{x:.2f}",
                f"{y:.2f}",
                f"{math.degrees(heading):.1f}",
                f"{lane.length:.2f}",
                f"{lane.speed_limit:.2f}",
                "yes" if lane.is_junction else "no",
                "-" if lane.stop_line_s is None else f"{lane.stop_line_s:.2f}",
                ",".join(lane.traffic_light_ids) or "-",
                ",".join(lane.successors) or "-",
            )
        )
    return rows


def light_rows(lane_map: LaneMap) -> list[tuple[str, ...]]:
    """Header and one row per traffic light: where it stands, what it governs."""
    rows: list[tuple[str, ...]] = [
        ("light", "x", "y", "z", "heading_deg", "type", "intersection", "lanes"),
    ]
    for light in lane_map.traffic_lights.values():
        x, y, z = light.position
        rows.append(
            (
                light.id,
                f"{x:.2f}",
                f"{y:.2f}",
                f"{z:.2f}",
                f"{math.degrees(light.heading):.1f}",
                str(light.light_type),
                str(light.intersection_id),
                ",".join(light.lane_ids) or "-",
            )
        )
    return rows


def crosswalk_rows(lane_map: LaneMap) -> list[tuple[str, ...]]:
    """Header and one row per crosswalk: its ends (walking direction) and width."""
    rows: list[tuple[str, ...]] = [
        ("crosswalk", "start_x", "start_y", "end_x", "end_y", "width_m", "intersection"),
    ]
    for crosswalk in lane_map.crosswalks.values():
        rows.append(
            (
                crosswalk.id,
                f"{crosswalk.start[0]:.2f}",
                f"{crosswalk.start[1]:.2f}",
                f"{crosswalk.end[0]:.2f}",
                f"{crosswalk.end[1]:.2f}",
                f"{crosswalk.width:.2f}",
                "-" if crosswalk.intersection_id is None else str(crosswalk.intersection_id),
            )
        )
    return rows


def _georeference(georef: GeoReference) -> str:
    lat, lon, _ = georef.local_to_geodetic(0.0, 0.0, 0.0)
    grid = georef.projection or f"UTM zone {georef.utm_zone}{'N' if georef.northern else 'S'}"
    placed = (
        f"{grid}, local origin at easting {georef.origin_east:.3f} m, northing "
        f"{georef.origin_north:.3f} m, altitude {georef.origin_up:.3f} m "
        f"(lat {lat:.6f}, lon {lon:.6f})"
    )
    if georef.assumed:
        return (
            f"assumed, the map names none: {placed}, where the built-in maps are; "
            "GPS latitudes and longitudes are invented"
        )
    return placed


def _print_table(rows: Sequence[tuple[str, ...]], what: str) -> None:
    print()
    if len(rows) == 1:
        print(f"no {what}")
        return
    widths = [max(len(row[i]) for row in rows) for i in range(len(rows[0]))]
    for row in rows:
        print(
            "  ".join(cell.ljust(width) for cell, width in zip(row, widths, strict=True)).rstrip()
        )


def _write_png(lane_map: LaneMap, path: Path, size: int, junction_ids: bool) -> int:
    # matplotlib takes 0.6-1.2 s to import: every egosim command would pay it at start.
    from ..plots import figure_png, map_figure  # noqa: PLC0415

    figure, drawn = map_figure(lane_map, max_px=size, junction_lane_ids=junction_ids)
    try:
        path.write_bytes(figure_png(figure))
    except OSError as error:
        print(f"egosim map: cannot write {path}: {error.strerror}", file=sys.stderr)
        return EXIT_BAD_INPUT
    width, height = figure.canvas.get_width_height()
    labelled = [lane for lane in lane_map.lanes.values() if junction_ids or not lane.is_junction]
    print(
        f"\nwrote {path} ({width} x {height} px): {len(drawn.lanes)} of {len(labelled)} "
        f"{'lane' if junction_ids else 'road lane'} ids and {len(drawn.lights)} of "
        f"{len(lane_map.traffic_lights)} light ids labelled"
        + ("" if len(drawn.lanes) == len(labelled) else "; the rest had no room: see --lanes")
    )
    return 0
