"""A drive read back from a bag egosim recorded: the ego's series, its collisions and the
light states it was shown, as numpy arrays in SI units on the bag's time axis."""

from __future__ import annotations

import logging
import os
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Final

import numpy as np
from rosbags.interfaces import Connection
from rosbags.rosbag1 import Reader, ReaderError
from rosbags.typesys.msg import denormalize_msgtype

from egosim.msgs import PROFILES, MsgsError
from egosim.replay import DEFAULT_TOPICS, BagError, BagTimeline, MissingTopicsError, ReplayTopics
from egosim.replay.releases import bag_release
from egosim.world.arrays import FloatArray
from egosim.world.collision import ContactTracker

if TYPE_CHECKING:
    from egosim.msgs.typed import morai_24_r2, morai_26_r1, morai_2021_08, standard
    from egosim.replay.releases import BagRelease

    CollisionData = (
        morai_26_r1.CollisionData | morai_24_r2.CollisionData | morai_2021_08.CollisionData
    )
    """A CollisionData of any release."""

log = logging.getLogger(__name__)

COLLISION_TYPE: Final = "morai_msgs/CollisionData"
LIGHT_STATUS_TYPE: Final = "morai_msgs/GetTrafficLightStatus"
#: The ego's side of each contact pair the tracker follows (one topic: one ego).
EGO_SIDE = -1


@dataclass(frozen=True)
class RecordedCollision:
    """A contact of the ego /CollisionData listed: when it was first listed, where (the
    other object's position then), with what. A contact is listed in every message while it
    lasts; touching again within REJOIN_S of parting is the same contact, as the simulator
    counts collisions (world/collision.py)."""

    time_s: float
    x: float
    y: float
    name: str
    unique_id: int
    object_type: int


@dataclass(frozen=True)
class LightState:
    """A light's aspect (protocol bits) as /GetTrafficLightStatus showed it at `time_s`."""

    time_s: float
    light_id: str
    aspect: int


@dataclass(frozen=True, eq=False)
class RecordedDrive:
    """The ego's EgoVehicleStatus series (times in s from the bag's first message), in SI:
    position m, heading rad (unwrapped), forward speed m/s, pedals 0..1, steering rad."""

    path: Path
    profile: str
    times_s: FloatArray
    x: FloatArray
    y: FloatArray
    heading: FloatArray
    speed_mps: FloatArray
    accel_pedal: FloatArray
    brake_pedal: FloatArray
    front_steer_rad: FloatArray
    collisions: tuple[RecordedCollision, ...]
    """Contacts that began during the recording."""
    contacts_at_start: tuple[RecordedCollision, ...]
    """Contacts already listed by the bag's first /CollisionData message: under way when
    the recording began (a bag `egosim record` wrote next to a running simulator may begin
    while the ego rests against what it hit long before), so not collisions of this drive."""
    light_states: tuple[LightState, ...]

    @property
    def xy(self) -> FloatArray:
        return np.column_stack((self.x, self.y))


def read_drive(
    path: str | os.PathLike[str], *, topics: ReplayTopics = DEFAULT_TOPICS
) -> RecordedDrive:
    """The drive recorded in the bag at `path` (by `egosim run --record` or `egosim record`).

    The ego comes from `topics.ego`; collisions and light states from every connection
    of type CollisionData / GetTrafficLightStatus, whatever its topic name. Raises
    FileNotFoundError, BagError (unreadable, no ego messages, unknown release).
    """
    timeline = BagTimeline.open(path, topics=topics)
    if timeline.ego is None:
        raise MissingTopicsError(f"{path} has no {topics.ego} messages")
    ego = timeline.ego
    columns = ego.columns
    events = _read_events(timeline)
    return RecordedDrive(
        path=timeline.path,
        profile=timeline.profile,
        times_s=ego.times,
        x=columns[:, 0],
        y=columns[:, 1],
        heading=columns[:, 9],
        # EgoVehicleStatus.velocity is in the vehicle frame: x is the forward speed.
        speed_mps=columns[:, 3],
        accel_pedal=columns[:, 10],
        brake_pedal=columns[:, 11],
        front_steer_rad=columns[:, 12],
        collisions=events.collisions,
        contacts_at_start=events.contacts_at_start,
        light_states=events.lights,
    )


@dataclass(frozen=True)
class _Events:
    collisions: tuple[RecordedCollision, ...]
    contacts_at_start: tuple[RecordedCollision, ...]
    lights: tuple[LightState, ...]


def _read_events(timeline: BagTimeline) -> _Events:
    # collision topic -> (t, message)
    listings: dict[str, list[tuple[float, CollisionData]]] = {}
    lights: list[LightState] = []

    def time_s(header: standard.Header) -> float:
        return (header.stamp.sec * 10**9 + header.stamp.nanosec - timeline.start_ns) / 1e9

    try:
        with Reader(timeline.path) as reader:
            releases = _event_connections(reader.connections, timeline.profile)
            wanted = [c for c in reader.connections if c.id in releases]
            for connection, _, raw in reader.messages(connections=wanted):
                release = releases[connection.id]
                if denormalize_msgtype(connection.msgtype) == LIGHT_STATUS_TYPE:
                    light = release.message(LIGHT_STATUS_TYPE).deserialize(raw)
                    lights.append(
                        LightState(
                            time_s(light.header),
                            light.trafficLightIndex,
                            int(light.trafficLightStatus),
                        )
                    )
                else:
                    collision = release.message(COLLISION_TYPE).deserialize(raw)
                    listings.setdefault(connection.topic, []).append(
                        (time_s(collision.header), collision)
                    )
    except (ReaderError, KeyError, ValueError, MsgsError) as exc:
        raise BagError(f"cannot read {timeline.path}: {exc}") from exc
    collisions: list[RecordedCollision] = []
    at_start: list[RecordedCollision] = []
    for messages in listings.values():
        began, under_way = _contacts(sorted(messages, key=lambda m: m[0]))
        collisions += began
        at_start += under_way
    return _Events(
        tuple(sorted(collisions, key=lambda c: c.time_s)),
        tuple(sorted(at_start, key=lambda c: c.time_s)),
        tuple(sorted(lights, key=lambda s: s.time_s)),
    )


def _contacts(
    messages: list[tuple[float, CollisionData]],
) -> tuple[list[RecordedCollision], list[RecordedCollision]]:
    """The contacts that one topic's CollisionData messages (by time) list, each once, at
    its first listing: (those that began in the recording, those the first message lists)."""
    tracker = ContactTracker()
    began: list[RecordedCollision] = []
    under_way: list[RecordedCollision] = []
    for number, (t, message) in enumerate(messages):
        listed = {obj.unique_id: obj for obj in message.collision_object}
        for _, unique_id in tracker.begin([(EGO_SIDE, uid) for uid in listed], t):
            obj = listed[unique_id]
            contact = RecordedCollision(
                t, obj.position.x, obj.position.y, obj.name, obj.unique_id, obj.type
            )
            (under_way if number == 0 else began).append(contact)
    return began, under_way


def _event_connections(connections: Iterable[Connection], preferred: str) -> dict[int, BagRelease]:
    """The collision and light-status connections to read (by id), each with its release.

    A topic served to clients of several releases was recorded once per release: only one
    release of each topic is read (the ego's when it has it), so no event counts twice.
    """
    by_topic: dict[str, list[tuple[Connection, BagRelease]]] = {}
    order = [preferred, *(name for name in PROFILES if name != preferred)]
    for connection in connections:
        type_name = denormalize_msgtype(connection.msgtype)
        if type_name not in (COLLISION_TYPE, LIGHT_STATUS_TYPE):
            continue
        release = next(
            (
                bag_release(name)
                for name in order
                if bag_release(name).message(type_name).md5sum == connection.digest
            ),
            None,
        )
        if release is None:
            log.warning("%s: %s has an unknown md5sum; not read", connection.topic, type_name)
            continue
        by_topic.setdefault(connection.topic, []).append((connection, release))
    chosen: dict[int, BagRelease] = {}
    for candidates in by_topic.values():
        best = min(order.index(release.name) for _, release in candidates)
        chosen.update((c.id, r) for c, r in candidates if order.index(r.name) == best)
    return chosen
