"""What every row handler sees: the world, the message profile, the clock, and the
simulator-side state the protocol adds to the world (lamps, control modes, ...)."""

from __future__ import annotations

import logging
from collections.abc import Callable
from contextlib import AbstractContextManager, nullcontext
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..msgs import Profile
from ..replay import DEFAULT_TOPICS, ReplaySession, ReplayTopics
from ..world import World
from .messages import header

if TYPE_CHECKING:
    from ..world.traffic.autopilot import LaneAutopilot
    from .sensor_rig import SensorRig
    from .sync_mode import SyncSession

log = logging.getLogger(__name__)

MAP_FRAME = "map"

# EventInfo.ctrl_mode codes.
CTRL_MODE_KEYBOARD = 1
CTRL_MODE_GAMEPAD = 2
CTRL_MODE_EXTERNAL = 3
CTRL_MODE_AUTO = 4


@dataclass
class Lamps:
    """morai_msgs/Lamps state of one ego: 0 none / 1 left / 2 right; emergency 0 / 1."""

    turn_signal: int = 0
    emergency: int = 0


@dataclass
class EgoSettings:
    """Per-ego settings set through the protocol rather than by physics."""

    ctrl_mode: int = CTRL_MODE_EXTERNAL
    lamps: Lamps = field(default_factory=Lamps)


@dataclass
class BridgeContext:
    profile: Profile
    world: World
    stamp: Callable[[], float]
    """The simulator's clock for headers (s): wall time, or sim time with --clock sim/sync."""
    data_roots: tuple[Path, ...] = ()
    """Where file names from the network (scenarios, bags, sensor data) resolve."""
    camera_index: int = 0
    """The ego /Ego_topic reports (MultiEgoSetting.camera_index)."""
    ego_settings: dict[int, EgoSettings] = field(default_factory=dict)
    reported: dict[str, int] = field(default_factory=dict)
    """How many entries of each world log a publisher has already reported."""
    warned: set[str] = field(default_factory=set)
    """Warnings already logged, so repeated bad input is reported once."""
    step: Callable[[float], None] | None = None
    """Advance the world one step of the given dt (s) and publish what is due (set by the
    app; the sync-mode services call it)."""
    sensors: SensorRig | None = None
    """The main ego's GPS, IMU and LiDAR (set by the app from the network settings)."""
    sync: SyncSession | None = None
    """Synchronous-mode state; None unless the run uses --clock sync."""
    publishes_clock: bool = False
    """Headers carry simulation time and /clock is published (--clock sim and sync)."""
    replay_topics: ReplayTopics = DEFAULT_TOPICS
    """Where a replayed bag holds the ego, object and command rows."""
    autopilots: dict[int, LaneAutopilot] = field(default_factory=dict)
    """The autopilot of each ego in control mode auto, by unique id."""
    open_row: Callable[[str, str, Callable[..., Any]], Callable[[], None] | None] | None = None
    """(row key, namespace, handler): open a topic row under a namespace at run time;
    returns what closes it, None if the row is disabled (set by the app: Bridge.open_row)."""
    holding_output: Callable[[], AbstractContextManager[None]] = nullcontext
    """A block whose topic output reaches subscribers as one burst when it ends (set by
    the app: Node.holding_output); sync mode ticks a WaitForTick's frames inside one."""
    ego_rows: dict[int, list[Callable[[], None]]] = field(default_factory=dict)
    """What closes the namespaced topics of each additional ego, by unique id."""
    replay: ReplaySession = field(init=False)
    """The rosbag replay system behind /Morai_SimProc; bags resolve in data_roots."""

    def __post_init__(self) -> None:
        self.replay = ReplaySession(
            self.data_roots, profile=self.profile.name, topics=self.replay_topics
        )

    def header(self, frame_id: str = MAP_FRAME) -> Any:
        return header(self.profile, self.stamp(), frame_id)

    def warn_once(self, key: str, text: str) -> None:
        """Log `text` the first time `key` comes up, so a 50 Hz stream of the same bad
        input does not flood the log."""
        if key not in self.warned:
            self.warned.add(key)
            log.warning(text)

    def settings_of(self, unique_id: int) -> EgoSettings:
        return self.ego_settings.setdefault(unique_id, EgoSettings())

    def unreported(self, log_name: str, entries: list[Any]) -> list[Any]:
        """Entries of a growing world log not yet published (all of them after a reset)."""
        done = self.reported.get(log_name, 0)
        if done > len(entries):
            done = 0
        self.reported[log_name] = len(entries)
        return entries[done:]
