"""What the page's buttons and keys do to the simulation.

Requests arrive as JSON objects from the browser; the server hands each to the loop
thread through the app's inbox (like any ROS command) and `ViewControls.apply` runs it
there, between two steps. Bad requests are answered with an error, never raised.
"""

from __future__ import annotations

import logging
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import ClassVar

from ..bridge import BridgeContext, ControlMode
from ..bridge.scene.scenarios import log_scenario_loaded, scenario_path
from ..bridge.scene.storyboard import scenario_drives_ego
from ..datapaths import PathOutsideRootsError
from ..json_value import JsonObject, JsonValue
from ..replay.codes import SET_START_TIME, CommandResult, PlaybackStatus, ProcessCommand
from ..scenario_files import looks_like_scenario, read_scenario_file
from ..world.scenario import Scenario, ScenarioError, ScenarioLoadOptions
from ..world.vehicle import Vehicle
from .keyboard import HeldKeys, KeyboardDriver
from .messages import Reply, ReplyFields

log = logging.getLogger(__name__)

#: Control modes the page offers: keyboard, external (ROS /ctrl_cmd), autopilot.
PAGE_CTRL_MODES = (ControlMode.KEYBOARD, ControlMode.EXTERNAL, ControlMode.AUTO)
#: At most this many scenario files are listed (a data root may be a large tree).
MAX_LISTED_SCENARIOS = 200


class ControlError(Exception):
    """A request the simulation cannot honour; the message says why, for the page."""


@dataclass(frozen=True)
class _Read:
    """A scenario read from its file, and what reads that file again (reload)."""

    scenario: Scenario
    again: Callable[[], Scenario]


def _read_file(path: Path, roots: tuple[Path, ...]) -> _Read | ControlError:
    def parse() -> Scenario:
        return read_scenario_file(path, roots=roots)

    try:
        return _Read(parse(), parse)
    except (OSError, UnicodeDecodeError, ScenarioError) as error:
        return ControlError(f"scenario {path.name!r} not loaded: {error}")


@dataclass(frozen=True)
class PreparedRequest:
    """A page request with its file work done on the server thread (ViewControls.prepare):
    a load's or reload's scenario read, or why it could not be."""

    request: JsonValue
    read: _Read | ControlError | None = None


@dataclass(frozen=True)
class _ReplayCommand:
    """A MoraiSimProcHandle as the replay session reads it, made by the page."""

    sim_process_status: int
    replay_option: int = 0
    rosbag_file_name: str = ""
    replay_target_option: int = 0
    replay_speed: int = 1
    start_time: int = 0  # ms


@dataclass
class ViewControls:
    """Applies page requests to the world (loop thread only)."""

    context: BridgeContext
    reload_source: Callable[[], Scenario] | None
    """The scenario the run started with (None: nothing to reload)."""
    pause_after_step: bool = False
    """Set by a single-step request: the view stage pauses the world after the next step."""
    _keyboards: dict[int, KeyboardDriver] = field(default_factory=dict)

    def apply(self, request: JsonValue | PreparedRequest) -> Reply:
        """Run one request (as the page sent it, or prepared); the reply for the page
        ({"ok": ...} and an "error" text)."""
        prepared = request if isinstance(request, PreparedRequest) else PreparedRequest(request)
        fields = prepared.request
        op = fields.get("op") if isinstance(fields, dict) else None
        if not isinstance(fields, dict) or not isinstance(op, str):
            return {"ok": False, "error": "a request is an object with an 'op' string"}
        handler = self._HANDLERS.get(op)
        if handler is None:
            return {"ok": False, "error": f"unknown request {op!r}"}
        try:
            result = handler(self, fields, prepared.read)
        except ControlError as error:
            log.warning("view: %s refused: %s", op, error)
            return {"ok": False, "op": op, "error": str(error)}
        done: Reply = {"ok": True, "op": op}
        return {**done, **(result or {})}

    # -- time -------------------------------------------------------------------------

    def _own_time(self, action: str) -> None:
        if self.context.sync.holds_time:
            raise ControlError(f"cannot {action} in sync mode: the client steps the simulation")

    def pause(self, _: JsonObject, __: _Read | ControlError | None) -> None:
        self._own_time("pause")
        self.context.world.paused = True

    def resume(self, _: JsonObject, __: _Read | ControlError | None) -> None:
        self._own_time("resume")
        self.pause_after_step = False
        self.context.world.paused = False

    def step(self, _: JsonObject, __: _Read | ControlError | None) -> None:
        self._own_time("step")
        self.context.world.paused = False
        self.pause_after_step = True

    # -- scenarios --------------------------------------------------------------------

    def scenarios(self, _: JsonObject, __: _Read | ControlError | None) -> ReplyFields:
        """Scenario files in the data roots, as names a load request takes."""
        names: list[str] = []
        for root in self.context.data_roots:
            base = Path(root).resolve()
            for path in sorted(base.rglob("*")):
                if len(names) >= MAX_LISTED_SCENARIOS:
                    break
                if looks_like_scenario(path):
                    names.append(path.relative_to(base).as_posix())
        return {"scenarios": names}

    def prepare(self, request: JsonValue) -> PreparedRequest:
        """`request` with its file work done (server thread): a load or reload reads and
        parses its scenario here, so the loop only applies it."""
        op = request.get("op") if isinstance(request, dict) else None
        if op == "load" and isinstance(request, dict):
            return PreparedRequest(request, self._read_named(request.get("name")))
        if op == "reload":
            return PreparedRequest(request, self._read_again())
        return PreparedRequest(request)

    def _read_named(self, name: JsonValue) -> _Read | ControlError:
        if not isinstance(name, str) or not name:
            return ControlError("load needs a scenario 'name'")
        try:
            path = scenario_path(name, self.context.data_roots)
        except (PathOutsideRootsError, OSError) as error:
            return ControlError(f"scenario {name!r} not loaded: {error}")
        return _read_file(path, tuple(self.context.data_roots))

    def _read_again(self) -> _Read | ControlError:
        source = self.reload_source
        if source is None:
            return ControlError("this run started without a scenario: nothing to reload")
        try:
            return _Read(source(), source)
        except (OSError, UnicodeDecodeError, ScenarioError) as error:
            return ControlError(f"scenario not reloaded: {error}")

    def load(self, request: JsonObject, read: _Read | ControlError | None) -> ReplyFields:
        name = request.get("name")
        read = read or self._read_named(name)
        if isinstance(read, ControlError):
            raise read
        assert isinstance(name, str)  # a read scenario was named
        self._load(read.scenario)
        self.reload_source = read.again
        return {"loaded": name}

    def reload(self, _: JsonObject, read: _Read | ControlError | None) -> None:
        read = read or self._read_again()
        if isinstance(read, ControlError):
            raise read
        self._load(read.scenario)

    def _load(self, scenario: Scenario) -> None:
        try:
            options = ScenarioLoadOptions(scenario_drives_ego=scenario_drives_ego(self.context))
            report = self.context.world.load_scenario(scenario, options)
        except ScenarioError as error:
            raise ControlError(str(error)) from error
        self._keyboards.clear()
        log_scenario_loaded(scenario, report, "the view")

    # -- driving ----------------------------------------------------------------------

    def _ego_index(self, request: JsonObject) -> int:
        index = request.get("ego", 0)
        if not isinstance(index, int) or not 0 <= index < len(self.context.world.egos):
            raise ControlError(f"no ego {index!r}")
        return index

    def ctrl_mode(self, request: JsonObject, _: _Read | ControlError | None) -> None:
        mode = request.get("mode")
        if mode not in PAGE_CTRL_MODES:
            raise ControlError(f"control mode {mode!r} is not one of {PAGE_CTRL_MODES}")
        ego = self.context.world.egos[self._ego_index(request)]
        self.context.ego_session(ego).set_ctrl_mode(ControlMode(int(mode)), by="the view")

    def keys(self, request: JsonObject, _: _Read | ControlError | None) -> None:
        ego = self.context.world.egos[self._ego_index(request)]
        if self.context.ego_session(ego).ctrl_mode is not ControlMode.KEYBOARD:
            raise ControlError("the ego is not in keyboard control mode")
        if not isinstance(ego.vehicle, Vehicle):
            raise ControlError("keyboard driving needs a road vehicle")
        held = HeldKeys(*(request.get(k) is True for k in ("throttle", "brake", "left", "right")))
        driver = self._keyboards.setdefault(ego.unique_id, KeyboardDriver())
        driver.drive(ego.vehicle, held)

    def release_silent_keyboards(self) -> None:
        """Brake every keyboard-driven ego whose page stopped sending keys (loop thread,
        every tick); an ego no longer in keyboard mode is let go of."""
        egos = {ego.unique_id: ego for ego in self.context.world.egos}
        for unique_id, driver in list(self._keyboards.items()):
            ego = egos.get(unique_id)
            keyboard = (
                ego is not None
                and self.context.ego_session(ego).ctrl_mode is ControlMode.KEYBOARD
                and isinstance(ego.vehicle, Vehicle)
            )
            if not keyboard:
                del self._keyboards[unique_id]
            elif (
                ego is not None and isinstance(ego.vehicle, Vehicle) and driver.silent(ego.vehicle)
            ):
                driver.release(ego.vehicle)
                del self._keyboards[unique_id]

    # -- replay -----------------------------------------------------------------------

    def replay(self, request: JsonObject, _: _Read | ControlError | None) -> None:
        session = self.context.replay
        if session.timeline is None:
            raise ControlError("no bag loaded for replay")
        action = request.get("action")
        if action == "play":
            command = _ReplayCommand(int(ProcessCommand.PLAY))
        elif action == "pause":
            command = _ReplayCommand(int(ProcessCommand.PAUSE))
        elif action == "seek":
            position = request.get("position")
            if not isinstance(position, int | float):
                raise ControlError("seek needs a 'position' in seconds")
            status = session.playback_status
            keep = ProcessCommand.PLAY if status is PlaybackStatus.RUNNING else ProcessCommand.PAUSE
            command = _ReplayCommand(
                int(keep), replay_option=SET_START_TIME[0], start_time=round(position * 1000)
            )
        else:
            raise ControlError(f"replay action {action!r} is not play, pause or seek")
        result = session.handle(command, received_ns=round(self.context.world.sim_time * 1e9))
        if result is not CommandResult.SUCCESS:
            raise ControlError(f"replay {action} failed: {result.name.lower()}")

    _HANDLERS: ClassVar[
        dict[
            str,
            Callable[[ViewControls, JsonObject, _Read | ControlError | None], ReplyFields | None],
        ]
    ] = {
        "pause": pause,
        "resume": resume,
        "step": step,
        "scenarios": scenarios,
        "load": load,
        "reload": reload,
        "ctrl_mode": ctrl_mode,
        "keys": keys,
        "replay": replay,
    }
