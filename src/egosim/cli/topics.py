"""`egosim topics`: the effective topic and service table."""

from __future__ import annotations

import argparse
import sys

from ..bridge.protocol.network import load_network_settings
from ..yamltext import YamlFileError


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.description = (
        "Every row of the MORAI protocol table as egosim will serve it, after "
        "the network settings file's overrides."
    )
    parser.add_argument("--network", metavar="PATH", help="network settings YAML file")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    try:
        settings = load_network_settings(args.network)
    except (OSError, YamlFileError) as exc:
        print(f"egosim topics: {exc}", file=sys.stderr)
        return 1
    print(f"ego input: {settings.ego_input}")
    header = ("key", "direction", "name", "type", "rate", "enabled")
    rows = [
        (
            row.key,
            row.direction.value,
            row.name,
            row.type_name,
            "-" if row.rate_hz is None else f"{row.rate_hz:g} Hz",
            "yes" if row.enabled else "no",
        )
        for row in settings.rows
    ]
    widths = [max(len(line[i]) for line in (header, *rows)) for i in range(len(header))]
    for line in (header, *rows):
        print(
            "  ".join(cell.ljust(width) for cell, width in zip(line, widths, strict=True)).rstrip()
        )
    return 0
