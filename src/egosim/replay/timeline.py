"""A recorded drive, opened from a bag and sampled at any time offset."""

from __future__ import annotations

import logging
import os
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Final, Generic, Protocol, TypeVar

import numpy as np
from rosbags.interfaces import Connection
from rosbags.rosbag1 import Reader, ReaderError
from rosbags.typesys.msg import denormalize_msgtype

from egosim.msgs import PROFILES, MsgsError

from .errors import BagError, BagInUseError, MissingTopicsError, UnsupportedReleaseError
from .frame import ReplayFrame
from .recordings import is_recording
from .releases import Decoder, bag_release
from .repair import needs_repair, repair_bag
from .tracks import ControlTrack, EgoTrack, ObjectTrack

if TYPE_CHECKING:
    from .releases import BagRelease
    from .tracks import CtrlCmd, EgoStatus, ObjectList

log = logging.getLogger(__name__)

M = TypeVar("M")
"""The messages of one topic (its type, in the bag's release)."""
Track = TypeVar("Track")

EGO_TYPE: Final = "morai_msgs/EgoVehicleStatus"
OBJECTS_TYPE: Final = "morai_msgs/ObjectStatusList"
CONTROL_TYPE: Final = "morai_msgs/CtrlCmd"


@dataclass(frozen=True)
class ReplayTopics:
    """The topic names a replay reads (MORAI's defaults; a network setting may rename them)."""

    ego: str = "/Ego_topic"
    objects: str = "/Object_topic"
    control: str = "/ctrl_cmd"

    def types(self) -> dict[str, str]:
        return {self.ego: EGO_TYPE, self.objects: OBJECTS_TYPE, self.control: CONTROL_TYPE}


DEFAULT_TOPICS = ReplayTopics()


@dataclass
class _Clocks:
    """A topic's two clocks per message: header stamp (0 if none) and receive time, ns."""

    header_ns: np.ndarray
    received_ns: np.ndarray


class _Reading(Protocol):
    """A topic being read from the bag, whatever its type."""

    def read(self, data: bytes | memoryview, received_ns: int) -> None: ...


@dataclass
class _Recorded(Generic[M]):
    """One topic's messages, decoded as they come out of the bag, with their clocks."""

    decoder: Decoder[M]
    stamp_ns: Callable[[M], int]
    """A message's header stamp, ns (0: none)."""
    messages: list[M] = field(default_factory=list)
    header_ns: list[int] = field(default_factory=list)
    received_ns: list[int] = field(default_factory=list)

    def read(self, data: bytes | memoryview, received_ns: int) -> None:
        message = self.decoder.deserialize(data)
        self.messages.append(message)
        self.header_ns.append(self.stamp_ns(message))
        self.received_ns.append(received_ns)

    def clocks(self) -> _Clocks:
        return _Clocks(
            np.array(self.header_ns, dtype=np.int64), np.array(self.received_ns, dtype=np.int64)
        )


def _header_stamp_ns(message: EgoStatus | ObjectList) -> int:
    stamp = message.header.stamp
    return stamp.sec * 10**9 + stamp.nanosec


def _unstamped(message: CtrlCmd) -> int:
    return 0  # CtrlCmd has no header


@dataclass
class _Decoded:
    """The replay topics' messages; a topic the bag lacks has none."""

    ego: _Recorded[EgoStatus]
    objects: _Recorded[ObjectList]
    control: _Recorded[CtrlCmd]

    @classmethod
    def of(cls, release: BagRelease) -> _Decoded:
        ego: Decoder[EgoStatus] = release.message(EGO_TYPE)
        objects: Decoder[ObjectList] = release.message(OBJECTS_TYPE)
        control: Decoder[CtrlCmd] = release.message(CONTROL_TYPE)
        return cls(
            _Recorded(ego, _header_stamp_ns),
            _Recorded(objects, _header_stamp_ns),
            _Recorded(control, _unstamped),
        )


class BagTimeline:
    """The ego, object and command topics of one bag, indexed by time.

    Time base: a message's time is its header stamp when non-zero (the
    simulator's clock at publication), else its receive time in the bag
    shifted onto the header clock by the median (stamp - receive time) of the
    stamped messages; CtrlCmd has no header and is always placed that way.
    `start_ns`/`end_ns` are the first and last message times on that clock;
    `sample(t)` takes t in s from `start_ns`.
    """

    def __init__(
        self,
        path: Path,
        profile: str,
        start_ns: int,
        end_ns: int,
        ego: EgoTrack | None,
        objects: ObjectTrack | None,
        control: ControlTrack | None,
    ) -> None:
        self.path = path
        self.profile = profile
        self.start_ns = start_ns
        self.end_ns = end_ns
        self.ego = ego
        self.objects = objects
        self.control = control

    @property
    def duration(self) -> float:
        """s from the first to the last replayed message."""
        return (self.end_ns - self.start_ns) / 1e9

    @classmethod
    def open(
        cls,
        path: str | os.PathLike[str],
        *,
        profile: str | None = None,
        topics: ReplayTopics = DEFAULT_TOPICS,
    ) -> BagTimeline:
        """Read the replay topics of the bag at `path`, repairing its index if it has none.

        `profile` (a morai_msgs release) is detected from the connections' md5sums
        when not given. Raises FileNotFoundError, BagError (unreadable),
        UnsupportedReleaseError, MissingTopicsError.
        """
        path = Path(path)
        if is_recording(path):
            raise BagInUseError(f"{path} is still being recorded")
        if not path.is_file():
            raise FileNotFoundError(f"no bag at {path}")
        if needs_repair(path):
            log.warning("%s has no index (its recorder did not close it); repairing", path)
            repair_bag(path)
        try:
            with Reader(path) as reader:
                connections = _replay_connections(reader.connections, topics)
                release = _matching_release(connections, profile)
                decoded = _decode(reader, connections, release, topics)
        except (ReaderError, KeyError, ValueError) as exc:  # ValueError: text that is not UTF-8
            raise BagError(f"cannot read {path}: {exc}") from exc
        return cls._from_decoded(path, release.name, decoded, sorted(connections))

    @classmethod
    def _from_decoded(
        cls, path: Path, profile: str, decoded: _Decoded, topics: list[str]
    ) -> BagTimeline:
        clocks = [r.clocks() for r in (decoded.ego, decoded.objects, decoded.control)]
        offset_ns = _receive_to_header_offset(clocks)
        times = [np.where(c.header_ns != 0, c.header_ns, c.received_ns + offset_ns) for c in clocks]
        if not any(len(t) for t in times):
            raise MissingTopicsError(f"{path} has no messages on {topics}")
        start_ns = min(int(t.min()) for t in times if len(t))
        end_ns = max(int(t.max()) for t in times if len(t))
        ego_times, object_times, control_times = times
        return cls(
            path,
            profile,
            start_ns,
            end_ns,
            _track(decoded.ego.messages, ego_times, start_ns, EgoTrack.from_messages),
            _track(decoded.objects.messages, object_times, start_ns, ObjectTrack.from_messages),
            _track(decoded.control.messages, control_times, start_ns, ControlTrack.from_messages),
        )

    def sample(self, t: float) -> ReplayFrame:
        """The recorded scene `t` s after the start (held at the ends).

        Ego state is interpolated between the messages around t; objects come
        from the latest ObjectStatusList at or before t, each interpolated
        towards the next list when that list has it too; the command is the
        latest at or before t.
        """
        t = min(max(t, 0.0), self.duration)
        npcs, pedestrians, obstacles = self.objects.sample(t) if self.objects else ((), (), ())
        return ReplayFrame(
            time=t,
            stamp_ns=self.start_ns + round(t * 1e9),
            ego=self.ego.sample(t) if self.ego else None,
            npcs=npcs,
            pedestrians=pedestrians,
            obstacles=obstacles,
            control=self.control.sample(t) if self.control else None,
        )


def _replay_connections(
    connections: Iterable[Connection], topics: ReplayTopics
) -> dict[str, list[Connection]]:
    """The bag's connections on replay topics, by topic, checked for the expected type."""
    expected = topics.types()
    found: dict[str, list[Connection]] = {}
    for connection in connections:
        if connection.topic not in expected:
            continue
        type_name = denormalize_msgtype(connection.msgtype)
        if type_name != expected[connection.topic]:
            raise BagError(
                f"{connection.topic} carries {type_name}, expected {expected[connection.topic]}"
            )
        found.setdefault(connection.topic, []).append(connection)
    if not found:
        raise MissingTopicsError(f"the bag has none of the topics {sorted(expected)}")
    return found


def _track(
    messages: Sequence[M],
    times_ns: np.ndarray,
    start_ns: int,
    build: Callable[[np.ndarray, Sequence[M]], Track],
) -> Track | None:
    """A topic's track, its messages in time order (times in s from `start_ns`); None
    when it has none."""
    if not len(times_ns):
        return None
    order = np.argsort(times_ns, kind="stable")
    return build((times_ns[order] - start_ns) / 1e9, [messages[k] for k in order])


def _matching_release(connections: dict[str, list[Connection]], profile: str | None) -> BagRelease:
    """The morai_msgs release whose md5sums every replay connection carries."""
    candidates = [profile] if profile else list(PROFILES)
    seen = {(denormalize_msgtype(c.msgtype), c.digest) for cs in connections.values() for c in cs}
    for name in candidates:
        release = bag_release(name)
        if all(release.message(type_name).md5sum == md5 for type_name, md5 in seen):
            return release
    known = "; ".join(
        f"{name}: "
        + ", ".join(f"{t} {bag_release(name).message(t).md5sum}" for t, _ in sorted(seen))
        for name in candidates
    )
    raise UnsupportedReleaseError(
        "the bag's morai_msgs md5sums ("
        + ", ".join(f"{t} {md5}" for t, md5 in sorted(seen))
        + f") match no supported release ({known})"
    )


def _decode(
    reader: Reader,
    connections: dict[str, list[Connection]],
    release: BagRelease,
    topics: ReplayTopics,
) -> _Decoded:
    decoded = _Decoded.of(release)
    reading: dict[str, _Reading] = {
        topics.ego: decoded.ego,
        topics.objects: decoded.objects,
        topics.control: decoded.control,
    }
    wanted = [c for cs in connections.values() for c in cs]
    for connection, received, raw in reader.messages(connections=wanted):
        try:
            reading[connection.topic].read(raw, received)
        except MsgsError as exc:
            raise BagError(f"corrupt message on {connection.topic}: {exc}") from exc
    return decoded


def _receive_to_header_offset(decoded: Iterable[_Clocks]) -> int:
    """Median (header stamp - receive time) over stamped messages, ns; 0 when none is stamped."""
    differences = [d.header_ns[d.header_ns != 0] - d.received_ns[d.header_ns != 0] for d in decoded]
    stamped = np.concatenate(differences) if differences else np.zeros(0, dtype=np.int64)
    return int(np.median(stamped)) if len(stamped) else 0
