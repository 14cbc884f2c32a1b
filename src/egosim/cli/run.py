"""`egosim run`: the simulator."""

from __future__ import annotations

import argparse
import logging
import sys
from pathlib import Path

from ..app.options import RunOptions
from ..app.runner import run as run_simulator
from ..app.signals import CLEAN_STOP_DEADLINE_S, exit_now
from ..bridge import ClockMode
from ..bridge.protocol.codes import ControlMode
from ..msgs import DEFAULT_PROFILE, PROFILES
from ..view import DEFAULT_HOST, DEFAULT_PORT, ViewOptions, live_view
from .arguments import LOG_LEVELS, non_negative_float, positive_float


def port_number(text: str) -> int:
    value = int(text)
    if not 0 <= value <= 65535:
        raise argparse.ArgumentTypeError(f"expected a port 0..65535, got {text}")
    return value


def parameter_assignment(text: str) -> tuple[str, str]:
    name, equals, value = text.partition("=")
    if not equals or not name.strip():
        raise argparse.ArgumentTypeError(f"expected NAME=VALUE, got {text!r}")
    return name.strip(), value


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.description = (
        "Start the simulator: joins the ROS master at ROS_MASTER_URI, or starts "
        "one there when none answers. Extra ROS arguments (__name:=, __ns:=, from:=to) "
        "are accepted after the options."
    )
    parser.add_argument(
        "--map",
        metavar="NAME|PATH",
        help="built-in map (town, straight, loop, mgeo_sample), MGeo folder or OpenDRIVE "
        ".xodr file (default: the scenario's map, else town); with --scenario it must be "
        "the map the scenario is for",
    )
    parser.add_argument(
        "--scenario",
        type=Path,
        metavar="PATH",
        help="scenario: egosim YAML or OpenSCENARIO .xosc; runs on the map it names (the "
        "town has a default scenario). An OpenSCENARIO run ends when its storyboard does",
    )
    parser.add_argument(
        "--ctrl-mode",
        choices=("external", "auto"),
        default="external",
        help="the ego's control mode at start: external (its stack drives, the default) or "
        "auto (egosim drives it: an OpenSCENARIO scenario's own actions, else the autopilot)",
    )
    parser.add_argument(
        "--param",
        action="append",
        default=[],
        type=parameter_assignment,
        metavar="NAME=VALUE",
        help="set a parameter an OpenSCENARIO scenario declares (repeatable)",
    )
    parser.add_argument(
        "--keep-running",
        action="store_true",
        help="keep running after an OpenSCENARIO scenario's storyboard has ended",
    )
    parser.add_argument("--network", type=Path, metavar="PATH", help="network settings YAML")
    parser.add_argument("--clock", choices=[m.value for m in ClockMode], default="real")
    parser.add_argument(
        "--rtf",
        type=non_negative_float,
        default=1.0,
        metavar="FACTOR",
        help="real-time factor with --clock sim (0: as fast as possible)",
    )
    parser.add_argument(
        "--duration",
        type=positive_float,
        metavar="SECONDS",
        help="stop after this much simulated time",
    )
    parser.add_argument(
        "--record", type=Path, metavar="BAG", help="write every topic and command to a bag"
    )
    parser.add_argument(
        "--protocol",
        choices=PROFILES,
        default=DEFAULT_PROFILE,
        help="morai_msgs release for peers that accept any (all are served)",
    )
    parser.add_argument("--log-level", choices=LOG_LEVELS, default="INFO", type=str.upper)
    parser.add_argument(
        "--data-root",
        type=Path,
        action="append",
        default=[],
        metavar="DIR",
        help="directory that scenario, bag and sensor-data names from the network resolve "
        "in (repeatable; default: the current directory)",
    )
    parser.add_argument(
        "--physics-rate",
        type=positive_float,
        default=100.0,
        metavar="HZ",
        help="physics steps per simulated second (default 100)",
    )
    view = parser.add_argument_group("live view")
    view.add_argument(
        "--view-host",
        default=DEFAULT_HOST,
        metavar="HOST",
        help=f"address the browser view listens on (default {DEFAULT_HOST}: this machine only)",
    )
    view.add_argument(
        "--view-port",
        type=port_number,
        default=DEFAULT_PORT,
        metavar="PORT",
        help=f"port of the browser view (default {DEFAULT_PORT}; 0: any free port)",
    )
    view.add_argument("--no-view", action="store_true", help="serve no browser view")
    view.add_argument(
        "--view-readonly",
        action="store_true",
        help="the view only shows: no pause, scenario loading or keyboard driving",
    )
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    if args.rtf != 1.0 and args.clock != ClockMode.SIM.value:
        # Wall-clock stamps on a world running at another pace would lie to every client.
        print("egosim: --rtf needs --clock sim", file=sys.stderr)
        return 2
    logging.basicConfig(
        level=args.log_level,
        stream=sys.stderr,
        format="%(asctime)s %(levelname)s %(name)s: %(message)s",
    )
    options = RunOptions(
        map=args.map,
        scenario=args.scenario,
        network=args.network,
        clock=ClockMode(args.clock),
        rtf=args.rtf,
        duration=args.duration,
        record=args.record,
        protocol=args.protocol,
        log_level=args.log_level,
        physics_rate_hz=args.physics_rate,
        data_roots=tuple(args.data_root),
        ros_argv=tuple(args.ros_args),
        ctrl_mode=ControlMode.AUTO if args.ctrl_mode == "auto" else ControlMode.EXTERNAL,
        keep_running=args.keep_running,
        scenario_parameters=tuple(args.param),
    )
    attach = []
    if not args.no_view:
        attach.append(live_view(ViewOptions(args.view_host, args.view_port, args.view_readonly)))
    exit_now(run_simulator(options, attach, stop_deadline_s=CLEAN_STOP_DEADLINE_S))
