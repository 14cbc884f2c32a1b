"""What every row handler sees: the world and the simulator's dependencies (message
profile, clock, tick pipeline, sensors, replay, sync mode), given at construction, and
the session state the protocol adds to the world (each ego's session: control mode,
lamps, autopilot, opened rows; the ego /Ego_topic reports, ...).

Build one with `egosim.bridge.simulation_context`.
"""

from __future__ import annotations

import logging
from collections.abc import Callable
from contextlib import AbstractContextManager, nullcontext
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Protocol, TypeVar

from ..logthrottle import LogThrottle
from ..msgs import TypedMessageType
from ..replay import ReplaySession
from ..world import World
from ..world.traffic import ObjectTable, SceneObjects
from .clock import HeaderClock
from .ego_session import EgoSession, EgoSessions
from .egos.angle_rates import AngleRates
from .pipeline import Tick, TickPipeline
from .protocol.messages import header
from .protocol.network import NetworkSettings
from .protocol.table import Row
from .sensors.sensor_rig import SensorRig
from .sync.sync_session import SyncSession

if TYPE_CHECKING:
    from ..msgs.typed import standard
    from ..world import Ego
    from .protocol.releases import CanonicalProfile
    from .sensors.camera_rig import CameraRig

log = logging.getLogger(__name__)
throttle = LogThrottle(log)

MAP_FRAME = "map"

Entry = TypeVar("Entry")
"""An entry of a world log (a collision, an event)."""
M = TypeVar("M")
"""The message a row opened at run time takes (a type of egosim.msgs.typed)."""


class RowBinder(Protocol):
    """Binds rows of the table at run time (the bridge): a topic row under a namespace
    (Bridge.open_publisher, Bridge.open_subscriber), e.g. the topics of an added ego, or
    a whole new table (Bridge.apply_settings)."""

    def open_publisher(
        self, key: str, namespace: str, build: Callable[[BridgeContext, Row], object]
    ) -> Callable[[], None] | None: ...

    def open_subscriber(
        self,
        key: str,
        namespace: str,
        takes: Callable[[CanonicalProfile], TypedMessageType[M]],
        handle: Callable[[BridgeContext, Row, M], None],
    ) -> Callable[[], None] | None: ...

    def apply_settings(self, settings: NetworkSettings) -> list[str]: ...


@dataclass
class SessionState:
    """What the protocol has set during this run, beside the world's own state."""

    camera_index: int = 0
    """The ego /Ego_topic reports (MultiEgoSetting.camera_index)."""
    egos: EgoSessions = field(default_factory=EgoSessions)
    """Each ego's session (control mode, lamps, autopilot, opened rows): the one
    owner of that state (bridge/ego_session.py)."""
    reported: dict[str, int] = field(default_factory=dict)
    """How many entries of each world log a publisher has already reported."""
    angle_rates: AngleRates = field(default_factory=AngleRates)
    """The last reading of each angle whose rate a row reports (extended status rows)."""


class TickReadings:
    """What several rows due in one tick read of the world, worked out once for all of
    them while the tick publishes (nothing moves the world then); outside that, each
    reading is taken afresh. The block in which readings are shared (a tick's publish
    stage) is a `with` block of this object. The loop thread's alone: the transport's
    threads read the world's clock itself."""

    def __init__(self) -> None:
        self._publishing = False
        self._scene: SceneObjects | None = None
        self._stamp_ns: int | None = None

    def __enter__(self) -> None:
        self._publishing = True

    def __exit__(self, *exc_info: object) -> None:
        self._publishing = False
        self._scene = None
        self._stamp_ns = None

    def stamp_ns(self, clock: HeaderClock) -> int:
        """The tick's header stamp (ns): every row of a tick reads the same one (see
        HeaderClock), so it is read once while the tick publishes."""
        if self._stamp_ns is not None:
            return self._stamp_ns
        stamp_ns = clock.now_ns()
        if self._publishing:
            self._stamp_ns = stamp_ns
        return stamp_ns

    def scene(self, world: World) -> SceneObjects:
        """Every object of `world` (World.scene_objects): the object list's, the LiDAR's,
        the radar's and the markers' scene."""
        if self._scene is not None:
            return self._scene
        scene = world.scene_objects()
        if self._publishing:
            self._scene = scene
        return scene


@dataclass
class BridgeContext:
    profile: CanonicalProfile
    """The release handlers build and read (the newest; releases.py converts)."""
    world: World
    clock: HeaderClock
    """The simulator's clock for headers: wall time, or sim time with --clock sim/sync."""
    pipeline: TickPipeline[BridgeContext]
    """What one tick does (bridge/stages.py); sync mode ticks through it."""
    settings: NetworkSettings
    """The effective protocol table: row names, rates, the ego's command input."""
    sensors: SensorRig
    """The main ego's GPS, IMU and LiDAR, as the network settings configure them."""
    replay: ReplaySession
    """The rosbag replay system behind /Morai_SimProc; bags resolve in data_roots."""
    sync: SyncSession[BridgeContext]
    """Synchronous mode: whether a client owns time, the frame, requests kept for later."""
    data_roots: tuple[Path, ...] = ()
    """Where file names from the network (scenarios, bags, sensor data) resolve."""
    cameras: CameraRig | None = None
    """Renders the main ego's cameras; None when none is configured or no renderer runs."""
    rows: RowBinder | None = None
    """Binds rows at run time (the bridge); None in-process, without a ROS node."""
    hold_output: Callable[[], AbstractContextManager[None]] = nullcontext
    """A block whose topic output reaches subscribers as one burst when it ends
    (Node.holding_output); sync mode ticks a WaitForTick's frames inside one."""
    session: SessionState = field(default_factory=SessionState)
    readings: TickReadings = field(default_factory=TickReadings)
    """World readings the rows due in one tick share (`objects`)."""

    def tick(self, dt: float) -> Tick:
        """Advance the simulation one tick of `dt` s through the pipeline."""
        return self.pipeline.run(self, dt)

    def objects(self) -> ObjectTable:
        """Every object of the world (World.objects), worked out once per tick for the
        rows that publish in it."""
        return self.readings.scene(self.world).table

    def scene_objects(self) -> SceneObjects:
        """`objects`, with how many of its rows are of each kind (World.scene_objects)."""
        return self.readings.scene(self.world)

    def row(self, key: str) -> Row:
        """The effective row `key` of the protocol table (its name and rate in use)."""
        return self.settings.row(key)

    def stamp(self) -> float:
        """The header stamp of this tick, s."""
        return self.clock()

    def stamp_ns(self) -> int:
        """The header stamp of this tick, ns."""
        return self.readings.stamp_ns(self.clock)

    def header(self, frame_id: str = MAP_FRAME) -> standard.Header:
        """A std_msgs/Header of this tick. A row's own header (its message's first field)
        gets its seq and stamp from its outlet as the message goes out, so a row that
        writes its own bytes leaves them zero: building it does not read the tick's stamp
        early (the first stamp asked for in a tick reads the wall clock in real time)."""
        return header(self.profile, self.stamp_ns(), frame_id)

    def warn_throttled(self, key: str, text: str) -> None:
        """Log `text` when `key` comes up, at most once per window with a count of the
        rest, so a 50 Hz stream of the same bad input does not flood the log."""
        throttle.log(logging.WARNING, key, "%s", text)

    def ego_session(self, ego: Ego) -> EgoSession:
        """The session of `ego`, the one owner of its run-time state."""
        return self.session.egos.of(ego)

    def unreported(self, log_name: str, entries: list[Entry]) -> list[Entry]:
        """Entries of a growing world log not yet published (all of them after a reset)."""
        reported = self.session.reported
        done = reported.get(log_name, 0)
        if done > len(entries):
            done = 0
        reported[log_name] = len(entries)
        return entries[done:]
