"""`egosim report`: an HTML page (and PNGs) of a drive recorded in a bag."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from ..app.exit_codes import EXIT_BAD_INPUT
from ..bridge.protocol.table import ROWS_BY_KEY
from ..maps import MapLoadError, load_map, map_names
from ..replay import BagError, ReplayTopics


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.description = (
        "Read a bag egosim recorded (egosim run --record, egosim record) and write "
        "a self-contained HTML page: the ego's trajectory over the map, its speed, steering, "
        "pedals, lateral and heading error against the lane, with collisions and red lights "
        "run marked on the time axis. Each figure is also written beside the page as a PNG."
    )
    parser.add_argument("bag", type=Path, metavar="BAG", help="the recorded bag")
    parser.add_argument(
        "-o", "--output", type=Path, required=True, metavar="HTML", help="the page to write"
    )
    parser.add_argument(
        "--map",
        metavar="NAME|PATH",
        help="the map the drive was on (default: the map egosim knows by name that its "
        "trajectory fits best)",
    )
    parser.add_argument(
        "--ego-topic",
        default=ROWS_BY_KEY["ego_status"].name,
        metavar="TOPIC",
        help="the ego's status topic (default: %(default)s)",
    )
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    # matplotlib takes 0.6-1.2 s to import: every egosim command would pay it at start.
    from ..report import best_fitting_map, read_drive, write_drive_report  # noqa: PLC0415

    try:
        drive = read_drive(args.bag, topics=ReplayTopics(ego=args.ego_topic))
    except (OSError, BagError) as error:
        print(f"egosim report: {error}", file=sys.stderr)
        return EXIT_BAD_INPUT
    if args.map is not None:
        try:
            lane_map = load_map(args.map)
        except MapLoadError as error:
            print(f"egosim report: {error}", file=sys.stderr)
            return EXIT_BAD_INPUT
        note = ""
    else:
        lane_map = best_fitting_map(drive.xy, (load_map(name) for name in map_names()))
        note = "the map egosim knows by name that the trajectory fits best; --map names another"
    if not args.output.parent.is_dir():
        print(f"egosim report: no folder {args.output.parent}", file=sys.stderr)
        return EXIT_BAD_INPUT
    written = write_drive_report(drive, lane_map, args.output, note)
    print(f"map: {lane_map.name}{f' ({note})' if note else ''}")
    for path in written:
        print(f"wrote {path}")
    return 0
