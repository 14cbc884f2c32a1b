"""A recorded drive, opened from a bag and sampled at any time offset."""

from __future__ import annotations

import logging
import os
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from rosbags.interfaces import Connection
from rosbags.rosbag1 import Reader, ReaderError
from rosbags.typesys.msg import denormalize_msgtype

from egosim.msgs import PROFILES, MessageType, MsgsError, Profile, get_profile

from .errors import BagError, BagInUseError, MissingTopicsError, UnsupportedReleaseError
from .frame import ReplayFrame
from .recordings import is_recording
from .repair import needs_repair, repair_bag
from .tracks import ControlTrack, EgoTrack, ObjectTrack

log = logging.getLogger(__name__)

EGO_TYPE = "morai_msgs/EgoVehicleStatus"
OBJECTS_TYPE = "morai_msgs/ObjectStatusList"
CONTROL_TYPE = "morai_msgs/CtrlCmd"


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
class _Decoded:
    """One topic's messages with their two clocks: header stamp (0 if none) and receive time."""

    messages: list[Any]
    header_ns: np.ndarray
    received_ns: np.ndarray


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
                decoded = _decode(reader, connections, release)
        except (ReaderError, KeyError, ValueError) as exc:  # ValueError: text that is not UTF-8
            raise BagError(f"cannot read {path}: {exc}") from exc
        return cls._from_decoded(path, release.name, decoded, topics)

    @classmethod
    def _from_decoded(
        cls, path: Path, profile: str, decoded: dict[str, _Decoded], topics: ReplayTopics
    ) -> BagTimeline:
        offset_ns = _receive_to_header_offset(decoded.values())
        times = {
            topic: np.where(d.header_ns != 0, d.header_ns, d.received_ns + offset_ns)
            for topic, d in decoded.items()
        }
        if not any(len(t) for t in times.values()):
            raise MissingTopicsError(f"{path} has no messages on {sorted(decoded)}")
        start_ns = min(int(t.min()) for t in times.values() if len(t))
        end_ns = max(int(t.max()) for t in times.values() if len(t))

        def track(topic: str, kind: Any) -> Any:
            if topic not in decoded or not len(times[topic]):
                return None
            order = np.argsort(times[topic], kind="stable")
            seconds = (times[topic][order] - start_ns) / 1e9
            messages = decoded[topic].messages
            return kind.from_messages(seconds, [messages[k] for k in order])

        return cls(
            path,
            profile,
            start_ns,
            end_ns,
            track(topics.ego, EgoTrack),
            track(topics.objects, ObjectTrack),
            track(topics.control, ControlTrack),
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


def _matching_release(connections: dict[str, list[Connection]], profile: str | None) -> Profile:
    """The morai_msgs release whose md5sums every replay connection carries."""
    candidates = [profile] if profile else list(PROFILES)
    seen = {(denormalize_msgtype(c.msgtype), c.digest) for cs in connections.values() for c in cs}
    for name in candidates:
        try:
            release = get_profile(name)
        except MsgsError as exc:
            raise UnsupportedReleaseError(str(exc)) from exc
        if all(release.message(type_name).md5sum == md5 for type_name, md5 in seen):
            return release
    known = "; ".join(
        f"{name}: "
        + ", ".join(f"{t} {get_profile(name).message(t).md5sum}" for t, _ in sorted(seen))
        for name in candidates
    )
    raise UnsupportedReleaseError(
        "the bag's morai_msgs md5sums ("
        + ", ".join(f"{t} {md5}" for t, md5 in sorted(seen))
        + f") match no supported release ({known})"
    )


def _decode(
    reader: Reader, connections: dict[str, list[Connection]], release: Profile
) -> dict[str, _Decoded]:
    types: dict[str, MessageType[object]] = {
        topic: release.message(denormalize_msgtype(cs[0].msgtype))
        for topic, cs in connections.items()
    }
    messages: dict[str, list[Any]] = {topic: [] for topic in connections}
    header_ns: dict[str, list[int]] = {topic: [] for topic in connections}
    received_ns: dict[str, list[int]] = {topic: [] for topic in connections}
    wanted = [c for cs in connections.values() for c in cs]
    for connection, received, raw in reader.messages(connections=wanted):
        try:
            message = types[connection.topic].deserialize(raw)
        except MsgsError as exc:
            raise BagError(f"corrupt message on {connection.topic}: {exc}") from exc
        stamp = message.header.stamp if hasattr(message, "header") else None
        messages[connection.topic].append(message)
        header_ns[connection.topic].append(stamp.sec * 10**9 + stamp.nanosec if stamp else 0)
        received_ns[connection.topic].append(received)
    return {
        topic: _Decoded(
            messages[topic],
            np.array(header_ns[topic], dtype=np.int64),
            np.array(received_ns[topic], dtype=np.int64),
        )
        for topic in connections
    }


def _receive_to_header_offset(decoded: Iterable[_Decoded]) -> int:
    """Median (header stamp - receive time) over stamped messages, ns; 0 when none is stamped."""
    differences = [d.header_ns[d.header_ns != 0] - d.received_ns[d.header_ns != 0] for d in decoded]
    stamped = np.concatenate(differences) if differences else np.zeros(0, dtype=np.int64)
    return int(np.median(stamped)) if len(stamped) else 0
