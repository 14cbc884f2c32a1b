"""The `egosim` command."""

from __future__ import annotations

import argparse
import os
import sys
from collections.abc import Callable, Sequence

from .. import __version__
from . import batch, map, msgs, record, report, run, topics


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="egosim",
        description="A headless driving simulator that speaks the MORAI SIM ROS 1 protocol.",
    )
    parser.add_argument("--version", action="version", version=f"egosim {__version__}")
    subparsers = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    run.add_parser(subparsers)
    msgs.add_parser(subparsers)
    topics.add_parser(subparsers)
    record.add_parser(subparsers)
    batch.add_parser(subparsers)
    map.add_parser(subparsers)
    report.add_parser(subparsers)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    args, extra = build_parser().parse_known_args(argv)
    # ROS's own command-line arguments (__name:=, from:=to) pass through to the node.
    ros_args = [arg for arg in extra if ":=" in arg]
    if len(ros_args) != len(extra) or (ros_args and args.command not in ("run", "record")):
        build_parser().error(f"unrecognized arguments: {' '.join(extra)}")
    args.ros_args = ros_args
    try:
        handler: Callable[[argparse.Namespace], int] = args.handler
        return handler(args)
    except BrokenPipeError:
        # Whoever read our output has gone (`egosim msgs | head`): not an error of ours.
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0
