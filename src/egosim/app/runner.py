"""`egosim run`: build the world, join (or start) the ROS master, serve, loop, stop cleanly."""

from __future__ import annotations

import contextlib
import logging
import sys
import threading
from collections.abc import Callable, Sequence
from pathlib import Path

from ..bridge import HANDLERS, Bridge, ClockMode, simulation_context
from ..bridge.network import load_network_settings
from ..maps import MapLoadError, load_map, scenario_map_location
from ..render import open_renderer
from ..replay import RecorderError
from ..ros1 import Node, Ros1Error
from ..world import World
from ..world.scenario import Scenario, ScenarioError, load_default_scenario, parse_scenario
from ..yamltext import YamlFileError
from .attachments import Attach, Attachment, RunningSimulator
from .exit_codes import EXIT_BAD_INPUT, EXIT_OK, EXIT_ROS_FAILED
from .inbox import Inbox
from .loop import SimulationLoop
from .options import RunOptions
from .recording import TopicRecorder, open_recorder
from .signals import StopControl, stop_on_signals
from .summary import ready_summary

log = logging.getLogger("egosim")

NODE_NAME = "egosim"
DEFAULT_MAP = "town"


class StartupError(Exception):
    """A startup failure with a one-line reason for the user."""

    def __init__(self, reason: str, exit_code: int = EXIT_BAD_INPUT) -> None:
        super().__init__(reason)
        self.exit_code = exit_code


def read_scenario_file(path: Path) -> Scenario:
    """The scenario in the file at `path` (OSError, UnicodeDecodeError, ScenarioError)."""
    return parse_scenario(path.read_text(encoding="utf-8"), str(path))


def startup_scenario(options: RunOptions, map_name: str) -> Callable[[], Scenario] | None:
    """What reads the scenario a run starts with: --scenario, else the town's default."""
    path = options.scenario
    if path is not None:
        return lambda: read_scenario_file(path)
    if map_name == DEFAULT_MAP:
        return load_default_scenario
    return None


def build_world(options: RunOptions) -> World:
    """The world of `options`: the scenario's own map unless --map names one (which must
    then be the map the scenario is for); no scenario: --map (default town)."""
    scenario = _read_scenario(options.scenario) if options.scenario is not None else None
    if options.map is not None:
        source = options.map
    elif scenario is not None and options.scenario is not None:
        source = scenario_map_location(scenario.map_reference, options.scenario.parent)
    else:
        source = DEFAULT_MAP
    try:
        lane_map = load_map(source)
    except MapLoadError as error:
        raise StartupError(f"map: {error}") from error
    if scenario is None and lane_map.name == DEFAULT_MAP:
        scenario = load_default_scenario()
    if scenario is not None and scenario.map_name != lane_map.name:
        raise StartupError(
            str(
                scenario.error(
                    ("map",),
                    f"the scenario is for map {scenario.map_name!r}, --map gives "
                    f"{lane_map.name!r} (leave --map out to run the scenario's own map)",
                )
            )
        )
    try:
        return World(lane_map, scenario, physics_step_s=options.physics_dt)
    except ScenarioError as error:
        raise StartupError(str(error)) from error


def _read_scenario(path: Path) -> Scenario:
    try:
        return read_scenario_file(path)
    except (OSError, UnicodeDecodeError) as error:
        raise StartupError(f"cannot read scenario {path}: {error}") from error
    except ScenarioError as error:
        raise StartupError(str(error)) from error


def run(
    options: RunOptions,
    attach: Sequence[Attach] = (),
    stop: threading.Event | None = None,
    *,
    stop_deadline_s: float | None = None,
) -> int:
    """Run the simulator until stopped; the process exit status.

    `attach` builds what rides on the loop (the live view, a batch case's drive) once the
    simulator is up; setting `stop` ends the run as Ctrl-C does. SIGINT, SIGTERM and
    `rosnode kill` stop it cleanly; a second signal ends the process at once with the bag
    closed, and so does a clean stop that overruns `stop_deadline_s` (see app/signals.py).
    """
    # Signals are handled from the start, before any bag exists: none ends the process
    # with a bag left open.
    with stop_on_signals(stop or threading.Event(), stop_deadline_s) as control:
        try:
            return _run(options, attach, control)
        except StartupError as error:
            print(f"egosim: {error}", file=sys.stderr)
            return error.exit_code


def _run(options: RunOptions, attach: Sequence[Attach], control: StopControl) -> int:
    world = build_world(options)
    try:
        settings = load_network_settings(
            str(options.network) if options.network is not None else None
        )
    except (OSError, YamlFileError) as error:
        raise StartupError(f"network settings: {error}") from error
    if control.stop.is_set():  # asked to stop while the map loaded: nothing to undo yet
        log.info("stopping: %s (during start-up)", control.reason)
        return EXIT_OK

    recorder = None
    if options.record is not None:
        try:
            recorder = TopicRecorder(open_recorder(options.record))
        except RecorderError as error:
            raise StartupError(f"--record: {error}") from error
        control.close_when_forced(recorder.close)

    # The bag is closed (index and header written) however the run ends.
    with recorder or contextlib.nullcontext():
        try:
            node = Node(NODE_NAME, list(options.ros_argv))
        except (OSError, Ros1Error) as error:
            reason = f"cannot join or start the ROS master: {error}"
            raise StartupError(reason, EXIT_ROS_FAILED) from error
        # `rosnode kill` stops the loop first; the node shuts down after it, below.
        node.on_shutdown_request(control.request)
        if _stopped_during_startup(control, node):
            return EXIT_OK
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
            open_renderer=open_renderer,
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
        if _stopped_during_startup(control, node):
            return EXIT_OK
        running = RunningSimulator(
            options, context, inbox, node, startup_scenario(options, world.map.name)
        )
        attachments: list[Attachment] = []
        try:
            attachments.extend(build(running) for build in attach)
        except StartupError:
            for attachment in attachments:
                attachment.close()
            node.shutdown("startup failed")
            raise
        log.info("egosim up: map %s, master %s", world.map.name, node.master_uri)
        print(f"egosim: ready\n{ready_summary(world, options)}", flush=True)

        max_steps = None
        if options.duration is not None:
            max_steps = round(options.duration / options.physics_dt)
        loop = SimulationLoop(
            lambda: context.tick(options.physics_dt),
            inbox,
            options.physics_dt,
            options.rtf,
            control.stop,
            max_steps,
            held=lambda: context.sync.holds_time,
        )
        try:
            loop.run()
            if control.reason is None:
                finished = max_steps is not None and loop.steps >= max_steps
                control.request(
                    f"--duration {options.duration:g} s simulated" if finished else "stop requested"
                )
        finally:
            control.stopping()
            log.info("stopping: %s", control.reason or "the loop failed")
            # Closed first: whoever still waits on the loop (a service call, a page's
            # request) gets its answer now, not at its timeout.
            inbox.close()
            for attachment in attachments:
                attachment.close()
            node.shutdown(control.reason or "egosim stopping")
    return EXIT_OK


def _stopped_during_startup(control: StopControl, node: Node) -> bool:
    """A stop asked for while the run was starting ends it before its next (long) step:
    registering every row, then building what rides on it. True if it did."""
    if not control.stop.is_set():
        return False
    log.info("stopping: %s (during start-up)", control.reason)
    node.shutdown(control.reason or "stop requested")
    return True
