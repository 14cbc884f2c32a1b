"""The simulator of one case, as a simulator worker (egosim.batch.worker) runs it.

Reads CASE_DIR/case.json, joins the case's own ROS master (its supervisor's: each case
has one, with an empty graph and parameter server), runs `egosim run` with the case's
scenario and a drive observer on the tick pipeline, and writes CASE_DIR/score.json
however the drive ends (route done, blocked, time limit, or stopped by its supervisor).
Its `master`, `running` and `ended` lines on stdout (worker_protocol) tell the
supervisor how far it got.
"""

from __future__ import annotations

import json
import os
import resource
import threading
import time
from collections.abc import Callable, Mapping
from pathlib import Path

import numpy as np
import yaml

from egosim.app.attachments import RunningSimulator
from egosim.app.options import RunOptions
from egosim.app.runner import run
from egosim.batch.case import CaseSpec
from egosim.batch.documents import Drive, ScoreFile
from egosim.batch.files import BAG_FILE, CASE_FILE, MORAI_SCENARIO_FILE, SCENARIO_FILE, SCORE_FILE
from egosim.batch.ros_graph import stack_connected
from egosim.batch.worker_protocol import ENDED, MASTER, PREFIX, RUNNING, SERVING
from egosim.bridge import ClockMode
from egosim.bridge.context import BridgeContext
from egosim.bridge.pipeline import Stage, Tick
from egosim.evaluation import DriveEvaluator, EvaluationSettings, InfractionKind, Route
from egosim.evaluation.route import RouteError
from egosim.scenario_files import is_morai_scenario
from egosim.sensors.camera_render import CameraRenderer
from egosim.world import World
from egosim.world.map import LaneMap

CONNECT_POLL_S = 0.25
PHYSICS_RATE_HZ = 100.0


def evaluation_settings(scoring: Mapping[str, object]) -> EvaluationSettings:
    """A suite's `scoring` (its schema checked the kinds and numbers)."""
    defaults = EvaluationSettings()
    penalties = dict(defaults.penalties)
    given = scoring.get("penalties")
    if isinstance(given, Mapping):
        penalties.update({InfractionKind(k): _number(v, 1.0) for k, v in given.items()})
    return EvaluationSettings(
        penalties=penalties,
        blocked_after_s=_number(scoring.get("blocked_after_s"), defaults.blocked_after_s),
        lane_departure_margin_m=_number(
            scoring.get("lane_departure_margin_m"), defaults.lane_departure_margin_m
        ),
    )


def _number(value: object, default: float) -> float:
    return float(value) if isinstance(value, int | float) else default


def build_route(lane_map: LaneMap, spec: Mapping[str, object] | None) -> Route | None:
    """A case's `route`: {"waypoints": [[x, y], ...]} or {"lanes": [...]}, optionally with
    "first_m" (its schema checked the shapes)."""
    if spec is None:
        return None
    if "lanes" in spec:
        lanes = spec["lanes"]
        if not isinstance(lanes, list):
            raise RouteError(f"lanes are a list of lane ids, not {lanes!r}")
        route = Route.through_lanes(lane_map, [str(lane) for lane in lanes])
    else:
        route = Route(np.asarray(spec["waypoints"], dtype=np.float64))
    first_m = spec.get("first_m")
    return route.first(first_m) if isinstance(first_m, int | float) else route


class CaseDrive:
    """The drive stage of the tick pipeline (right after the world's step): holds the
    world until the stack is connected (sim clock), then evaluates every step and ends
    the run (sets `stop`) when the drive is over.

    The drive's first sample is the world before its first step: in sync mode the first
    tick the stack asks for is where the drive begins, and with a coarse tick (up to 1 s)
    that tick alone may carry the ego over a stop line, which only a sample before it
    can see."""

    def __init__(self, case: CaseSpec, master_uri: str, stop: threading.Event) -> None:
        self.case = case
        self.master_uri = master_uri
        self.stop = stop
        self.over = False
        self.evaluator: DriveEvaluator | None = None
        self.end = "stopped"
        self.started_wall: float | None = None
        self.start_sim_s = 0.0
        self._next_poll = 0.0
        self._gate = case.clock == ClockMode.SIM.value
        self.world: World | None = None

    def attach(self, running: RunningSimulator) -> CaseDrive:
        """Ride on the run: the drive stage right after the world's step (the simulator
        serves every topic and service by now: the supervisor is told so)."""
        context = running.context
        world = self.world = context.world
        if self._gate:  # the sim clock's world waits for the stack from its first step on
            world.paused = True
        self.start_sim_s = world.sim_time
        try:
            route = build_route(world.map, self.case.route)
        except RouteError as error:
            self.end = f"bad route: {error}"  # the run ends at its first tick
        else:
            self.evaluator = DriveEvaluator(world, route, evaluation_settings(self.case.scoring))
            self.evaluator.observe(world)
        context.pipeline = context.pipeline.with_stage(Stage("drive", self.run), after="world")
        print(f"{PREFIX}{SERVING}", flush=True)
        return self

    def close(self) -> None:
        """Nothing to stop: the stage ends with the run."""

    def run(self, context: BridgeContext, tick: Tick) -> None:
        if self.over:  # the loop ends after this tick
            return
        self.world = context.world
        self.over = self._observe(context.world)
        if self.over:
            print(f"{PREFIX}{ENDED} {self.end}", flush=True)
            self.stop.set()

    def _observe(self, world: World) -> bool:
        if self.evaluator is None:  # the case's route does not fit the map
            return True
        if self.started_wall is None:
            if self._gate and not self._stack_ready(world):
                return False
            self._start(world)
            if self._gate:  # the world waited: it begins to move at the next step
                return False
        self.evaluator.observe(world)
        storyboard = world.storyboard
        if storyboard is not None and storyboard.finished:
            self.end = f"scenario {storyboard.outcome().state}"
            return True
        if (reason := self.evaluator.finish_reason) is not None:
            self.end = reason
            return True
        if world.sim_time - self.start_sim_s >= self.case.time_limit_s - 1e-9:
            self.end = "time_limit"
            return True
        return False

    def _stack_ready(self, world: World) -> bool:
        """Paused, at about real-time pace, until the stack has joined the graph."""
        world.paused = True
        now = time.monotonic()
        if now >= self._next_poll:
            self._next_poll = now + CONNECT_POLL_S
            if stack_connected(self.master_uri):
                return True
        time.sleep(world.physics_step_s)
        return False

    def _start(self, world: World) -> None:
        """The drive begins: the stack is there (sim clock) or stepped the world (sync)."""
        world.paused = False
        self.started_wall = time.monotonic()
        print(f"{PREFIX}{RUNNING}", flush=True)

    def result(self) -> Drive:
        wall = 0.0 if self.started_wall is None else time.monotonic() - self.started_wall
        score = None
        if self.evaluator is not None and self.started_wall is not None:  # the drive began
            score = self.evaluator.score(timed_out=self.end == "time_limit").as_dict()
        sim_time = 0.0 if self.world is None else self.world.sim_time - self.start_sim_s
        result: Drive = {
            "end": self.end,
            "sim_time_s": sim_time,
            "drive_wall_s": wall,
            "score": score,
        }
        storyboard = None if self.world is None else self.world.storyboard
        if storyboard is not None:
            outcome = storyboard.outcome()
            result["scenario"] = {
                "state": outcome.state,
                "time_s": outcome.time,
                "verdict": outcome.verdict,
            }
        return result


def _cpu_s() -> float:
    """User + system CPU time of this process so far."""
    usage = resource.getrusage(resource.RUSAGE_SELF)
    return usage.ru_utime + usage.ru_stime


def simulate_case(
    case_dir: Path,
    master_uri: str,
    stop: threading.Event,
    renderer: Callable[[], CameraRenderer],
) -> int:
    """Drive the case in `case_dir` on the ROS master at `master_uri` (its supervisor's)
    until its drive ends or `stop` is set; the run's exit status. The process's
    ROS_MASTER_URI and ROS_IP are the case's afterwards (the worker puts its environment
    back)."""
    cpu_before = _cpu_s()
    case = CaseSpec.from_dict(json.loads((case_dir / CASE_FILE).read_text(encoding="utf-8")))
    if case.openscenario:
        scenario_path = Path(case.openscenario)
    elif is_morai_scenario(Path(case.scenario_file)):
        scenario_path = case_dir / MORAI_SCENARIO_FILE
        scenario_path.write_text(json.dumps(case.scenario, indent=1), encoding="utf-8")
    else:
        scenario_path = case_dir / SCENARIO_FILE
        scenario_path.write_text(yaml.safe_dump(case.scenario, sort_keys=False), encoding="utf-8")
    os.environ["ROS_MASTER_URI"] = master_uri
    os.environ.setdefault("ROS_IP", "127.0.0.1")
    print(f"{PREFIX}{MASTER} {master_uri}", flush=True)
    drive = CaseDrive(case, master_uri, stop)
    options = RunOptions(
        map=case.map,
        scenario=scenario_path,
        clock=ClockMode(case.clock),
        rtf=case.rtf if case.clock == ClockMode.SIM.value else 1.0,
        record=None if case.bags == "none" else case_dir / BAG_FILE,
        log_level="WARNING",
        physics_rate_hz=PHYSICS_RATE_HZ,
        data_roots=(case_dir,),
        scenario_parameters=tuple(case.scenario_parameters.items()),
        # The drive stage ends the run, with the scenario's end among its reasons.
        keep_running=True,
        # Most cases take no camera frame; the worker keeps the scene once built.
        camera_scene_at_first_frame=True,
    )
    status = run(options, [drive.attach], stop, handle_signals=False, renderer=renderer)
    result: ScoreFile = {
        "exit_status": status,
        **drive.result(),
        "cpu_s": _cpu_s() - cpu_before,
    }
    (case_dir / SCORE_FILE).write_text(json.dumps(result), encoding="utf-8")
    return status
