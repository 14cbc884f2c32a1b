"""Rosbag recording and replay of the MORAI protocol's topics.

Recording (the bridge hands over bytes it already serialised)::

    with BagRecorder(path) as recorder:
        ego = recorder.add_connection("/Ego_topic", t.name, t.md5sum, t.definition)
        recorder.write(ego, stamp_ns, data)  # never waits for the disk

Replay (/Morai_SimProc)::

    session = ReplaySession(data_roots)
    session.handle(proc_handle_msg, received_ns=sim_time_ns)  # -> CommandResult
    session.advance(dt)                                       # each simulation step
    session.frame(), session.status()                         # ReplayFrame, ProcStatus
"""

from .codes import (
    CommandResult,
    Mode,
    PlaybackStatus,
    ProcessCommand,
    ReplayOptions,
    ReplayTargets,
)
from .errors import (
    BagError,
    BagInUseError,
    MissingTopicsError,
    RecorderError,
    ReplayError,
    UnsupportedReleaseError,
)
from .frame import ControlCommand, EgoState, ObjectState, ReplayFrame
from .recorder import BagRecorder, ConnectionHandle, RecorderStats
from .repair import RepairReport, needs_repair, repair_bag
from .session import ProcHandleCommand, ProcStatus, ReplaySession
from .timeline import DEFAULT_TOPICS, BagTimeline, ReplayTopics

__all__ = [
    "DEFAULT_TOPICS",
    "BagError",
    "BagInUseError",
    "BagRecorder",
    "BagTimeline",
    "CommandResult",
    "ConnectionHandle",
    "ControlCommand",
    "EgoState",
    "MissingTopicsError",
    "Mode",
    "ObjectState",
    "PlaybackStatus",
    "ProcHandleCommand",
    "ProcStatus",
    "ProcessCommand",
    "RecorderError",
    "RecorderStats",
    "RepairReport",
    "ReplayError",
    "ReplayFrame",
    "ReplayOptions",
    "ReplaySession",
    "ReplayTargets",
    "ReplayTopics",
    "UnsupportedReleaseError",
    "needs_repair",
    "repair_bag",
]
