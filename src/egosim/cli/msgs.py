"""`egosim msgs`: list every type with its md5sum, or show one (like rosmsg/rossrv)."""

from __future__ import annotations

import argparse
import sys

from ..msgs import DEFAULT_PROFILE, PROFILES, MsgsError, get_profile


def add_parser(subparsers: argparse._SubParsersAction) -> None:
    parser = subparsers.add_parser(
        "msgs",
        help="list message and service types with their md5sums, or show one",
        description="Without TYPE: every message and service type of the profile with its "
        "md5sum. With TYPE: its md5sum and full definition.",
    )
    parser.add_argument("--profile", default=DEFAULT_PROFILE, choices=PROFILES)
    parser.add_argument("--md5", action="store_true", help="print only the md5sum of TYPE")
    parser.add_argument("type", nargs="?", metavar="TYPE", help="e.g. morai_msgs/CtrlCmd")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    profile = get_profile(args.profile)
    if args.type is None:
        for name in profile.message_names():
            print(f"{profile.message(name).md5sum}  msg  {name}")
        for name in profile.service_names():
            print(f"{profile.service(name).md5sum}  srv  {name}")
        return 0
    try:
        if args.type in profile.service_names():
            found = profile.service(args.type)
        else:
            found = profile.message(args.type)
    except MsgsError as exc:
        print(f"egosim msgs: {exc}", file=sys.stderr)
        return 1
    if args.md5:
        print(found.md5sum)
    else:
        print(f"# {found.name}  md5sum: {found.md5sum}  profile: {profile.name}")
        print(found.definition.rstrip("\n"))
    return 0
