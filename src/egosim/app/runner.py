"""`egosim run`: build the world, join (or start) the ROS master, serve, loop, stop cleanly."""

from __future__ import annotations

import contextlib
import logging
import sys
import threading
from collections.abc import Callable, Sequence
from pathlib import Path

from ..bridge import HANDLERS, Bridge, ClockMode, simulation_context
from ..bridge.protocol.codes import ControlMode
from ..bridge.protocol.network import load_network_settings
from ..maps import MapLoadError, load_map, scenario_map_location
from ..render import open_renderer
from ..replay import RecorderError
from ..ros1 import Node, Ros1Error
from ..scenario_files import read_scenario_file
from ..sensors.camera_render import CameraRenderer
from ..world import World
from ..world.scenario import Scenario, ScenarioError, ScenarioLoadOptions, load_default_scenario
from ..yamltext import YamlFileError
from .attachments import Attach, Attachment, RunningSimulator
from .drive_log import drive_log
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


def startup_scenario(options: RunOptions, map_name: str) -> Callable[[], Scenario] | None:
    """What reads the scenario a run starts with: --scenario, else the town's default."""
    path = options.scenario
    if path is not None:
        return lambda: read_scenario_file(path, dict(options.scenario_parameters) or None)
    if map_name == DEFAULT_MAP:
        return load_default_scenario
    return None


def build_world(options: RunOptions) -> World:
    """The world of `options`: the scenario's own map unless --map names one (which must
    then be the map the scenario is for); no scenario: --map (default town)."""
    scenario = _read_scenario(options) if options.scenario is not None else None
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
        world = World(lane_map, physics_step_s=options.physics_dt)
        if scenario is not None:
            drives = options.ctrl_mode is ControlMode.AUTO
            report = world.load_scenario(scenario, ScenarioLoadOptions(scenario_drives_ego=drives))
            for note in report.notes:
                log.warning("%s", note)
        return world
    except ScenarioError as error:
        raise StartupError(str(error)) from error


def _read_scenario(options: RunOptions) -> Scenario:
    path = options.scenario
    assert path is not None
    try:
        return read_scenario_file(path, dict(options.scenario_parameters) or None)
    except (OSError, UnicodeDecodeError) as error:
        raise StartupError(f"cannot read scenario {path}: {error}") from error
    except ScenarioError as error:
        raise StartupError(str(error)) from error


def _scenario_ended(world: World) -> bool:
    """The OpenSCENARIO storyboard the run started with has ended."""
    return world.storyboard is not None and world.storyboard.finished


def _report_scenario_end(world: World) -> None:
    storyboard = world.storyboard
    if storyboard is not None and storyboard.finished:
        outcome = storyboard.outcome()
        verdict = "" if outcome.verdict is None else f", evaluation {outcome.verdict}"
        log.info("scenario ended at t=%.2f s: %s%s", outcome.time, outcome.state, verdict)


def run(
    options: RunOptions,
    attach: Sequence[Attach] = (),
    stop: threading.Event | None = None,
    *,
    handle_signals: bool = True,
    renderer: Callable[[], CameraRenderer] = open_renderer,
    stop_deadline_s: float | None = None,
) -> int:
    """Run the simulator until stopped; the process exit status.

    `attach` builds what rides on the loop (the live view, a batch case's drive) once the
    simulator is up; setting `stop` ends the run as Ctrl-C does. SIGINT, SIGTERM and
    `rosnode kill` stop it cleanly; a second signal ends the process at once with the bag
    closed, and so does a clean stop that overruns `stop_deadline_s` (see app/signals.py).
    Without `handle_signals` no signal is handled: a caller that runs one simulation after
    another in a process handles them itself. `renderer` opens the cameras' engine (a
    process that runs many simulations opens one and shares it).
    """
    # Signals are handled from the start, before any bag exists: none ends the process
    # with a bag left open.
    control_scope = stop_on_signals(
        stop or threading.Event(), stop_deadline_s, signals=handle_signals
    )
    with control_scope as control:
        try:
            return _run(options, attach, control, renderer)
        except StartupError as error:
            print(f"egosim: {error}", file=sys.stderr)
            return error.exit_code


def _run(
    options: RunOptions,
    attach: Sequence[Attach],
    control: StopControl,
    renderer: Callable[[], CameraRenderer],
) -> int:
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
            open_renderer=renderer,
            camera_scene_at_first_frame=options.camera_scene_at_first_frame,
        )
        if recorder is not None:
            bridge.taps.append(recorder.tap())
        if (console_log := drive_log()) is not None:
            context.pipeline = console_log.on(context.pipeline)
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
        context.ego_session(world.egos[0]).set_ctrl_mode(options.ctrl_mode, by="--ctrl-mode")
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
            done=None if options.keep_running else lambda: _scenario_ended(world),
        )
        try:
            loop.run()
            if control.reason is None:
                finished = max_steps is not None and loop.steps >= max_steps
                if finished:
                    reason = f"--duration {options.duration:g} s simulated"
                elif _scenario_ended(world):
                    reason = "the scenario ended"
                else:
                    reason = "stop requested"
                control.request(reason)
            _report_scenario_end(world)
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
