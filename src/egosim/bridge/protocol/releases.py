"""Serving every morai_msgs release at once: which release a peer speaks, and how a
message reads in another release.

The bridge builds and handles every message in the newest release (26.r1, the
superset). A peer compiled against another release is recognised by the md5sum in
its connection header, and its messages are converted field by field: same-named
fields are copied (recursively, through nested types), renamed fields follow
RENAMED_FIELDS, moved fields follow MOVED_FIELDS, and a field the other side lacks
is dropped on the way out and, on the way in, takes the value IMPLIED_FIELDS gives
(what the older release meant without it) or else its ROS default.

A release's view of a type is built (its definitions parsed) when first used: whether a
release has the type is told from its profile's names alone, and negotiation tries the
default release first, so a process no peer of an older release connects to never
parses that release's types.
"""

from __future__ import annotations

import functools
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Final, TypeVar, cast

from rosbags.interfaces import Nodetype
from rosbags.interfaces.typing import FieldDesc
from rosbags.typesys.store import Typestore

from ...msgs import PROFILES, MessageType, ServiceType, get_profile
from ...msgs.defaults import default_message
from ...msgs.fulltext import BUILTIN_TIME_TYPES, element_desc
from ...msgs.message_type import TypedMessageType
from ...msgs.values import FieldValue, Message

if TYPE_CHECKING:
    from ...msgs.typed import morai_26_r1

    CanonicalProfile = morai_26_r1.ReleaseProfile
    """The profile handlers build and read, typed: each type's fields are known."""

CANONICAL_PROFILE: Final = "26.r1"

Source = TypeVar("Source")
Target = TypeVar("Target")

# type -> {field in 26.r1: the same field's name in older releases}
RENAMED_FIELDS: dict[str, dict[str, str]] = {
    "morai_msgs/CtrlCmd": {"front_steer": "steering"},
    "morai_msgs/EgoVehicleStatus": {"front_steer_angle": "wheel_angle"},
    "morai_msgs/SaveSensorData": {"custom_file_name": "custum_file_name"},
}
# type -> {field of an older release: dotted path of the same quantity in 26.r1}
MOVED_FIELDS: dict[str, dict[str, str]] = {
    "morai_msgs/GhostMessage": {"heading": "rotation.z"},  # 2021.08: yaw, deg
}

# type -> {field later releases added: its value in a message of a release without it}
IMPLIED_FIELDS: dict[str, dict[str, FieldValue]] = {
    # 2021.08 cannot choose the tick length: MORAI SIM ticks its fixed 20 ms step.
    "morai_msgs/SyncModeCmd": {"time_step": 20},
}


# service type -> {release: its name there} where a release named it differently
SERVICE_NAMES: dict[str, dict[str, str]] = {
    "morai_msgs/MoraiSimProcSrv": {"2021.08": "morai_msgs/MoraiSimpProcSrv"},
}


def _search_order(default: str) -> Iterator[str]:
    """Every release, `default` first, then the others newest first."""
    yield default
    yield from (name for name in PROFILES if name != default)


@dataclass(frozen=True)
class ServiceRelease:
    """One release's view of one service type, built on first use."""

    profile_name: str
    type_name: str  # the service's name in this release

    @functools.cached_property
    def service_type(self) -> ServiceType[object, object]:
        return get_profile(self.profile_name).service(self.type_name)


def service_releases_of(type_name: str, default: str) -> tuple[ServiceRelease, ...]:
    """Every release that has the service `type_name` (under its name there), default first."""
    found = []
    for name in _search_order(default):
        local_name = SERVICE_NAMES.get(type_name, {}).get(name, type_name)
        if get_profile(name).has_service(local_name):
            found.append(ServiceRelease(name, local_name))
    return tuple(found)


def service_release_for_md5(
    releases: tuple[ServiceRelease, ...], md5sum: str
) -> ServiceRelease | None:
    """The release a client's md5sum asks for (`*`: the default, first one); the releases
    after the one that matches are not built."""
    if md5sum == "*":
        return releases[0]
    return next((r for r in releases if r.service_type.md5sum == md5sum), None)


@dataclass(frozen=True)
class Release:
    """One release's view of one message type, built on first use."""

    profile_name: str
    type_name: str

    @functools.cached_property
    def message_type(self) -> MessageType[object]:
        return get_profile(self.profile_name).message(self.type_name)


def releases_of(type_name: str, default: str) -> tuple[Release, ...]:
    """Every release that has `type_name`, `default` first."""
    return tuple(
        Release(name, type_name)
        for name in _search_order(default)
        if get_profile(name).has_message(type_name)
    )


def release_for_md5(releases: tuple[Release, ...], md5sum: str) -> Release | None:
    """The first release whose type has `md5sum` (the default wins when several share it);
    the releases after it are not built."""
    return next((r for r in releases if r.message_type.md5sum == md5sum), None)


def convert(
    message: Source, source: TypedMessageType[Source], target: TypedMessageType[Target]
) -> Target:
    """`message`, of type `source`, as a message of `target` (same type, other release)."""
    if source.md5sum == target.md5sum and source.name == target.name:
        return cast(Target, message)  # the same type: a release's twin of source's class
    # made as the class registered for target's store_name, the one `Target` describes
    return cast(Target, _convert(message, target.store, target.store_name))


def _convert(message: object, store: Typestore, store_name: str) -> Message:
    """`message` (of any release) as a `store_name` of `store`, its fields read by name."""
    ros_name = store_name.replace("/msg/", "/", 1)
    renamed = RENAMED_FIELDS.get(ros_name, {})
    aliases = {**renamed, **{old: new for new, old in renamed.items()}}
    values: dict[str, FieldValue] = {}
    for name, desc in store.fielddefs[store_name][1]:
        source_name = name if hasattr(message, name) else aliases.get(name)
        if source_name is not None and hasattr(message, source_name):
            values[name] = _converted_field(message, source_name, desc, store)
        elif name in IMPLIED_FIELDS.get(ros_name, {}):
            values[name] = IMPLIED_FIELDS[ros_name][name]
    result = default_message(store, store_name, **values)
    for old_field, path in MOVED_FIELDS.get(ros_name, {}).items():
        if hasattr(result, old_field) and not hasattr(message, old_field):
            setattr(result, old_field, _get_path(message, path))
        elif hasattr(message, old_field) and not hasattr(result, old_field):
            _set_path(result, path, getattr(message, old_field))
    return result


def _converted_field(message: object, name: str, desc: FieldDesc, store: Typestore) -> FieldValue:
    """Field `name` of `message` as a field described by `desc` in `store` holds it."""
    element = element_desc(desc)
    if element[0] != Nodetype.NAME or element[1] in BUILTIN_TIME_TYPES:
        value: FieldValue = getattr(message, name)
        return value
    if desc[0] == Nodetype.NAME:
        return _convert(getattr(message, name), store, element[1])
    items: Sequence[object] = getattr(message, name)
    return [_convert(item, store, element[1]) for item in items]


def _get_path(message: object, path: str) -> FieldValue:
    *parents, last = path.split(".")
    for part in parents:
        message = getattr(message, part)
    value: FieldValue = getattr(message, last)
    return value


def _set_path(message: object, path: str, value: FieldValue) -> None:
    *parents, last = path.split(".")
    for part in parents:
        message = getattr(message, part)
    setattr(message, last, value)


def canonical(type_name: str) -> MessageType[object]:
    """The canonical release's `type_name`, named at run time (a row's type)."""
    return get_profile(CANONICAL_PROFILE).message(type_name)
