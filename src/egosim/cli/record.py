"""`egosim record`: a separate node that records a running simulator's topics into a bag."""

from __future__ import annotations

import argparse
import logging
import sys
import threading
from pathlib import Path

from ..app.exit_codes import EXIT_BAD_INPUT, EXIT_ROS_FAILED
from ..app.recording import TopicRecorder, open_recorder, record_from_network
from ..app.signals import CLEAN_STOP_DEADLINE_S, stop_on_signals
from ..bridge.protocol.network import load_network_settings
from ..bridge.protocol.table import Direction
from ..bridge.sensors.camera_rows import camera_topic_names
from ..replay import RecorderError
from ..ros1 import Ros1Error
from ..yamltext import YamlFileError
from .arguments import LOG_LEVELS, positive_float


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.description = (
        "Join the ROS master at ROS_MASTER_URI and record topics into a new bag "
        "(every topic egosim publishes, by default) until Ctrl-C or --duration."
    )
    parser.add_argument("bag", type=Path, metavar="BAG", help="the bag to write (must not exist)")
    parser.add_argument(
        "--topics", nargs="+", metavar="TOPIC", help="topics to record instead of the default"
    )
    parser.add_argument(
        "--network",
        type=Path,
        metavar="PATH",
        help="the simulator's network settings YAML, for its topic names",
    )
    parser.add_argument(
        "--duration", type=positive_float, metavar="SECONDS", help="stop after this wall time"
    )
    parser.add_argument("--log-level", choices=LOG_LEVELS, default="INFO", type=str.upper)
    parser.set_defaults(handler=record)


def published_topics(network: Path | None) -> list[str]:
    """Every topic of the effective table that egosim publishes, and the cameras'."""
    settings = load_network_settings(str(network) if network is not None else None)
    rows = [row.name for row in settings.enabled_rows() if row.direction is Direction.PUBLISH]
    return rows + [name for name in camera_topic_names(settings) if name not in rows]


def record(args: argparse.Namespace) -> int:
    logging.basicConfig(
        level=args.log_level,
        stream=sys.stderr,
        format="%(asctime)s %(levelname)s %(name)s: %(message)s",
    )
    try:
        topics = args.topics or published_topics(args.network)
    except (OSError, YamlFileError) as error:
        print(f"egosim record: network settings: {error}", file=sys.stderr)
        return EXIT_BAD_INPUT
    # Signals are handled before the bag exists: none can end the process with it open.
    with stop_on_signals(threading.Event(), CLEAN_STOP_DEADLINE_S) as control:
        try:
            recorder = TopicRecorder(open_recorder(args.bag))
        except RecorderError as error:
            print(f"egosim record: {error}", file=sys.stderr)
            return EXIT_BAD_INPUT
        control.close_when_forced(recorder.close)
        with recorder:
            try:
                record_from_network(recorder, topics, control, args.duration, args.ros_args)
            except (OSError, Ros1Error) as error:
                print(f"egosim record: cannot join the ROS master: {error}", file=sys.stderr)
                return EXIT_ROS_FAILED
    return 0
