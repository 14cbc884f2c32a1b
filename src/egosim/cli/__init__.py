"""The `egosim` command."""

from __future__ import annotations

import argparse
import gc
import importlib
import os
import sys
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, NoReturn

from .. import __version__

COMMANDS: dict[str, str] = {
    "run": "start the simulator",
    "msgs": "list message and service types with their md5sums, show one, or export them",
    "topics": "print the effective topic/service table",
    "record": "record a running simulator's topics into a ROS 1 bag",
    "batch": "run a stack through a suite of scenarios and score every drive",
    "map": "describe a map and draw it to a PNG",
    "report": "an HTML report (and PNGs) of a drive recorded in a bag",
}
"""Each subcommand and its line in `egosim --help`. Its module, egosim.cli.<name>, gives
its parser the rest: `add_arguments(parser)` (its description and options, and its
handler, set as the `handler` default)."""


if TYPE_CHECKING:
    _SubParsersAction = argparse._SubParsersAction[argparse.ArgumentParser]
else:  # generic to the type checker only
    _SubParsersAction = argparse._SubParsersAction


class _Subcommands(_SubParsersAction):
    """Only the subcommand the command line names is defined (its module imported), just
    before its arguments are parsed. Each module imports what its command runs on (the
    world and numba, the ROS bridge, the live view's server, matplotlib: over a second
    together), which no other command is to pay for; `egosim batch` starts its simulator
    workers before it imports its own."""

    def __call__(
        self,
        parser: argparse.ArgumentParser,
        namespace: argparse.Namespace,
        values: str | Sequence[object] | None,
        option_string: str | None = None,
    ) -> None:
        assert isinstance(values, list)
        chosen = self.choices.get(values[0])
        if chosen is not None and chosen.get_default("handler") is None:
            importlib.import_module(f"{__name__}.{values[0]}").add_arguments(chosen)
        super().__call__(parser, namespace, values, option_string)


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="egosim",
        description="A headless driving simulator that speaks the MORAI SIM ROS 1 protocol.",
    )
    parser.add_argument("--version", action="version", version=f"egosim {__version__}")
    subparsers = parser.add_subparsers(
        dest="command", required=True, metavar="COMMAND", action=_Subcommands
    )
    for name, summary in COMMANDS.items():
        subparsers.add_parser(name, help=summary)
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


def command() -> NoReturn:
    """The `egosim` program: `main`, then the process's exit. What a command imported
    (numpy, numba, matplotlib, rosbags: over a hundred thousand objects) is frozen out of
    the garbage collections the interpreter makes as it exits, which would walk it all for
    a quarter of a second to find nothing to free: every file and bag is closed by then."""
    status = main()
    gc.freeze()
    sys.exit(status)
