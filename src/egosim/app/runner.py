"""`egosim run`: build the world, join (or start) the ROS master, serve, loop, stop cleanly."""

from __future__ import annotations

import contextlib
import logging
import sys
import threading
from pathlib import Path

from ..bridge import HANDLERS, Bridge, ClockMode, simulation_context
from ..bridge.network import load_network_settings
from ..maps import MapLoadError, load_map
from ..replay import RecorderError
from ..ros1 import Node, Ros1Error
from ..world import World
from ..world.scenario import ScenarioError, load_default_scenario, parse_scenario
from ..yamltext import YamlFileError
from .inbox import Inbox
from .loop import SimulationLoop
from .options import RunOptions
from .recording import TopicRecorder, open_recorder
from .signals import stop_on_signals

log = logging.getLogger("egosim")

NODE_NAME = "egosim"
EXIT_OK = 0
EXIT_BAD_INPUT = 2
EXIT_ROS_FAILED = 3


class StartupError(Exception):
    """A startup failure with a one-line reason for the user."""

    def __init__(self, reason: str, exit_code: int = EXIT_BAD_INPUT) -> None:
        super().__init__(reason)
        self.exit_code = exit_code


def build_world(options: RunOptions) -> World:
    try:
        lane_map = load_map(options.map)
    except MapLoadError as error:
        raise StartupError(f"map: {error}") from error
    try:
        if options.scenario is not None:
            scenario = parse_scenario(
                options.scenario.read_text(encoding="utf-8"), str(options.scenario)
            )
        elif lane_map.name == "town":
            scenario = load_default_scenario()
        else:
            scenario = None
        return World(lane_map, scenario, physics_step_s=options.physics_dt)
    except (OSError, UnicodeDecodeError) as error:
        raise StartupError(f"cannot read scenario {options.scenario}: {error}") from error
    except ScenarioError as error:
        raise StartupError(str(error)) from error


def run(options: RunOptions) -> int:
    """Run the simulator until stopped; the process exit status."""
    try:
        return _run(options)
    except StartupError as error:
        print(f"egosim: {error}", file=sys.stderr)
        return error.exit_code


def _run(options: RunOptions) -> int:
    world = build_world(options)
    try:
        settings = load_network_settings(
            str(options.network) if options.network is not None else None
        )
    except (OSError, YamlFileError) as error:
        raise StartupError(f"network settings: {error}") from error

    recorder = None
    if options.record is not None:
        try:
            recorder = TopicRecorder(open_recorder(options.record))
        except RecorderError as error:
            raise StartupError(f"--record: {error}") from error

    stop = threading.Event()
    # The bag is closed (index and header written) however the run ends.
    with stop_on_signals(stop), recorder or contextlib.nullcontext():
        try:
            node = Node(NODE_NAME, list(options.ros_argv))
        except (OSError, Ros1Error) as error:
            reason = f"cannot join or start the ROS master: {error}"
            raise StartupError(reason, EXIT_ROS_FAILED) from error
        node.on_shutdown(lambda reason: stop.set())
        inbox = Inbox()
        # Messages are built in the newest release; peers of others get them converted.
        bridge = Bridge(node, settings, HANDLERS, inbox, options.protocol)
        context = simulation_context(
            world,
            settings=settings,
            clock_mode=options.clock,
            data_roots=options.data_roots or (Path.cwd(),),
            bridge=bridge,
            hold_output=node.holding_output,
        )
        if recorder is not None:
            bridge.taps.append(recorder.tap())
        try:
            bridge.open(context)
            if options.clock is not ClockMode.REAL:
                node.set_param("/use_sim_time", True)
        except (OSError, Ros1Error) as error:
            node.shutdown("startup failed")
            reason = f"cannot register with the ROS master: {error}"
            raise StartupError(reason, EXIT_ROS_FAILED) from error
        log.info("egosim up: map %s, master %s", world.map.name, node.master_uri)
        print("egosim: ready", flush=True)

        max_steps = None
        if options.duration is not None:
            max_steps = round(options.duration / options.physics_dt)
        loop = SimulationLoop(
            lambda: context.tick(options.physics_dt),
            inbox,
            options.physics_dt,
            options.rtf,
            stop,
            max_steps,
            held=lambda: context.sync.holds_time,
        )
        try:
            loop.run()
        finally:
            inbox.close()
            node.shutdown("egosim stopping")
    return EXIT_OK
