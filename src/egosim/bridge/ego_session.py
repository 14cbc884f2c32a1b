"""An ego's run-time state beside its physics, with one owner per ego.

What is set for an ego while it runs, other than by driving it, is no part of the
world: its control mode, its lamps, the autopilot of auto mode, and the topics opened
for an additional ego. MORAI sets them through EventInfo, /lamps and MultiEgoSetting,
the live view through its buttons. Each ego has one EgoSession, and only its methods
change that state; the protocol handlers and the page call them and read the rest as
read-only properties. Setting a control mode releases the command in force
(bridge/control_modes.py says why), whoever sets it.
"""

from __future__ import annotations

import logging
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass

from ..world import Ego
from ..world.traffic import LaneGraph
from ..world.traffic.autopilot import LaneAutopilot
from .protocol.codes import ControlMode

log = logging.getLogger(__name__)

# What closes one topic opened for an ego.
RowCloser = Callable[[], None]


@dataclass(frozen=True)
class Lamps:
    """morai_msgs/Lamps state of one ego: 0 none / 1 left / 2 right; emergency 0 / 1."""

    turn_signal: int = 0
    emergency: int = 0


class EgoSession:
    """The run-time state of one ego; only these methods change it."""

    def __init__(self, ego: Ego) -> None:
        self._ego = ego
        self._ctrl_mode = ControlMode.EXTERNAL
        self._lamps = Lamps()
        self._autopilot: LaneAutopilot | None = None
        self._rows: tuple[RowCloser, ...] = ()

    @property
    def ego(self) -> Ego:
        return self._ego

    @property
    def ctrl_mode(self) -> ControlMode:
        """Who drives the ego (EventInfo.ctrl_mode; external by default)."""
        return self._ctrl_mode

    @property
    def lamps(self) -> Lamps:
        return self._lamps

    @property
    def autopilot(self) -> LaneAutopilot | None:
        """The autopilot driving the ego in auto mode; None before it first drives and
        outside auto mode."""
        return self._autopilot

    @property
    def has_rows(self) -> bool:
        """Topics are open for this ego (an additional ego's namespaced rows)."""
        return bool(self._rows)

    def set_ctrl_mode(self, mode: ControlMode, by: str) -> None:
        """Put the ego in control mode `mode` as `by` (a row's name, "the view") asks. A
        change is logged, releases the command in force (the ego brakes until its new
        input commands it) and drops the autopilot, so auto mode chosen again plans
        afresh from wherever the ego is then."""
        if mode is self._ctrl_mode:
            return
        log.info(
            "ego %d: control mode %s -> %s (%s)",
            self._ego.unique_id,
            self._ctrl_mode.name.lower(),
            mode.name.lower(),
            by,
        )
        self._ctrl_mode = mode
        self._autopilot = None
        self._ego.vehicle.release_command()

    def set_lamps(self, lamps: Lamps) -> None:
        self._lamps = lamps

    def autopilot_on(self, graph: LaneGraph) -> LaneAutopilot:
        """The ego's autopilot in auto mode, made on `graph` when it first drives."""
        if self._ctrl_mode is not ControlMode.AUTO:
            raise ValueError(f"ego {self._ego.unique_id} is not in auto mode")
        if self._autopilot is None:
            self._autopilot = LaneAutopilot(graph)
        return self._autopilot

    def open_rows(self, closers: Sequence[RowCloser]) -> None:
        """Keep what closes the topics just opened for this ego."""
        self._rows = (*self._rows, *closers)

    def close_rows(self) -> None:
        """Close the topics opened for this ego (it left the world)."""
        rows, self._rows = self._rows, ()
        for close in rows:
            close()


class EgoSessions:
    """The session of each ego of the world, by unique id, made when first asked for."""

    def __init__(self) -> None:
        self._by_id: dict[int, EgoSession] = {}

    def of(self, ego: Ego) -> EgoSession:
        session = self._by_id.get(ego.unique_id)
        if session is None:
            session = self._by_id[ego.unique_id] = EgoSession(ego)
        return session

    def keep(self, egos: Iterable[Ego]) -> None:
        """Forget the sessions of egos other than `egos` (removed from the world), closing
        their topics."""
        present = {ego.unique_id for ego in egos}
        for unique_id in set(self._by_id) - present:
            self._by_id.pop(unique_id).close_rows()

    @property
    def autopilots(self) -> dict[int, LaneAutopilot]:
        """The autopilot of each ego that has one, by unique id."""
        return {
            unique_id: session.autopilot
            for unique_id, session in self._by_id.items()
            if session.autopilot is not None
        }
