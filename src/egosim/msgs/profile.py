"""A protocol profile: every type of one morai_msgs release plus the ROS standard types,
each parsed on its first use."""

from __future__ import annotations

import functools
import threading
from collections.abc import Iterable
from typing import TYPE_CHECKING, Literal, overload

from rosbags.interfaces import Nodetype
from rosbags.interfaces.typing import Typesdict
from rosbags.typesys import Stores, get_types_from_msg, get_typestore
from rosbags.typesys.msg import denormalize_msgtype, normalize_msgtype
from rosbags.typesys.store import Typestore

from . import fulltext
from .definitions import (
    DEFAULT_PROFILE,
    SERVICE_SEPARATOR,
    ServiceText,
    load_package_definitions,
)
from .errors import DefinitionError, UnknownTypeError
from .message_type import MessageType, ServiceType

if TYPE_CHECKING:
    from .typed import morai_24_r2, morai_26_r1, morai_2021_08


# rosbags' stand-ins for ROS 1's time and duration built-ins: not types a user names.
ROSBAGS_INTERNAL = "builtin_interfaces/"

# Standard types egosim publishes or that morai_msgs embeds; listed by `egosim msgs`.
STANDARD_TYPES: tuple[str, ...] = (
    "std_msgs/Header",
    "std_msgs/String",
    "geometry_msgs/Point",
    "geometry_msgs/Pose",
    "geometry_msgs/Quaternion",
    "geometry_msgs/Transform",
    "geometry_msgs/TransformStamped",
    "geometry_msgs/Twist",
    "geometry_msgs/Vector3",
    "sensor_msgs/Imu",
    "sensor_msgs/NavSatFix",
    "sensor_msgs/PointCloud2",
    "sensor_msgs/PointField",
    "sensor_msgs/CompressedImage",
    "nav_msgs/Odometry",
    "nav_msgs/Path",
    "rosgraph_msgs/Clock",
    "rosgraph_msgs/Log",
    "tf2_msgs/TFMessage",
    "visualization_msgs/MarkerArray",
)


class Profile:
    """Every type of one protocol release, ready to serialise.

    A type's definition is parsed when the type is first used (`message`, `service`,
    `own_text`), together with the types its fields name, so that a process pays only
    for the types it uses; `complete_store` parses every one, for what lists them all.
    A malformed definition raises DefinitionError, naming the type, on its first use
    (or on the first use of a type that embeds it). A profile is shared by threads: the
    parsing is serialised by a lock."""

    def __init__(self, name: str) -> None:
        self.name = name
        self._store = get_typestore(Stores.ROS1_NOETIC)
        # every message and service half the release ships, by store name: its own text
        self._texts: dict[str, str] = {}
        self._package_messages: list[str] = []
        self._services: dict[str, ServiceText] = {}
        for package in load_package_definitions(name):
            for short, text in package.messages.items():
                ros_name = f"{package.package}/{short}"
                self._texts[normalize_msgtype(ros_name)] = text
                self._package_messages.append(ros_name)
            for short, srv in package.services.items():
                ros_name = f"{package.package}/{short}"
                self._texts[normalize_msgtype(f"{ros_name}Request")] = srv.request
                self._texts[normalize_msgtype(f"{ros_name}Response")] = srv.response
                self._services[ros_name] = srv
        self._parsing = threading.RLock()
        self._complete = False
        self._messages: dict[str, MessageType[object]] = {}

    def _require(self, store_names: Iterable[str]) -> None:
        """Parse and register each of `store_names` the release ships and every shipped
        type their fields name that is not registered yet; rosbags' own types always are."""
        with self._parsing:
            parsed: Typesdict = {}
            todo = list(store_names)
            while todo:
                store_name = todo.pop()
                if (
                    store_name in parsed
                    or store_name in self._store.fielddefs
                    or store_name not in self._texts
                ):
                    continue
                parsed.update(self._parse(store_name))
                for _, desc in parsed[store_name][1]:
                    element = fulltext.element_desc(desc)
                    if element[0] == Nodetype.NAME:
                        todo.append(element[1])
            if parsed:
                self._store.register(parsed)

    def _parse(self, store_name: str) -> Typesdict:
        try:
            return get_types_from_msg(self._texts[store_name], store_name)
        except Exception as exc:
            ros_name = denormalize_msgtype(store_name)
            raise DefinitionError(f"{self.name}: cannot parse {ros_name}: {exc}") from exc

    def complete_store(self) -> Typestore:
        """The rosbags store with every type of the release parsed, for what goes through
        them all; the first call parses every type not used yet."""
        with self._parsing:
            if not self._complete:
                self._require(self._texts)
                self._complete = True
        return self._store

    def own_text(self, store_name: str) -> str:
        """The definition of `store_name` alone (`pkg/msg/Name`), as its .msg file has it."""
        if store_name in self._texts:
            self._require([store_name])
            return self._texts[store_name]
        return self._store.gendefhash(store_name, {})[0]

    def message(self, name: str) -> MessageType[object]:
        """The message type `pkg/Name` (also accepts rosbags' `pkg/msg/Name`)."""
        if found := self._messages.get(name):  # the hot path: builders ask per message
            return found
        ros_name = denormalize_msgtype(normalize_msgtype(name))
        with self._parsing:
            if ros_name not in self._messages:
                if not self.has_message(ros_name):
                    raise UnknownTypeError(f"no message type {name!r} in profile {self.name}")
                store_name = normalize_msgtype(ros_name)
                self._require([store_name])
                self._messages[ros_name] = MessageType(
                    name=ros_name,
                    md5sum=self._store.generate_msgdef(store_name)[1],
                    definition=fulltext.full_text(self._store, store_name, self.own_text),
                    store=self._store,
                )
            self._messages[name] = self._messages[ros_name]
        return self._messages[name]

    def has_message(self, name: str) -> bool:
        """Whether the release has the message type `name` (as `message` takes it), told
        without parsing it."""
        store_name = normalize_msgtype(name)
        return store_name in self._texts or store_name in self._store.fielddefs

    def has_service(self, name: str) -> bool:
        """Whether the release has the service type `pkg/Name`, told without parsing it."""
        return name in self._services

    def service(self, name: str) -> ServiceType[object, object]:
        """The service type `pkg/Name`."""
        if not self.has_service(name):
            raise UnknownTypeError(f"no service type {name!r} in profile {self.name}")
        request, response = self.message(f"{name}Request"), self.message(f"{name}Response")
        srv = self._services[name]
        return ServiceType(
            name=name,
            md5sum=fulltext.service_md5(self._store, request.store_name, response.store_name),
            request=request,
            response=response,
            definition=f"{srv.request}{SERVICE_SEPARATOR}\n{srv.response}",
        )

    def resolve(self, name: str) -> str:
        """The full name of the message or service type `name`, which may omit its package
        when only one type has that name (`CtrlCmd` -> `morai_msgs/CtrlCmd`)."""
        if "/" in name:
            return name
        halves = {f"{srv}{half}" for srv in self._services for half in ("Request", "Response")}
        known = [
            ros_name
            for store_name in self.complete_store().fielddefs
            if not store_name.startswith(ROSBAGS_INTERNAL)
            and (ros_name := denormalize_msgtype(store_name)) not in halves
        ]
        return resolve_short_name(name, [*known, *self._services], self.name)

    def message_names(self) -> list[str]:
        """The package's own message types, then the standard ones, each sorted."""
        package = sorted(set(self._package_messages) - set(STANDARD_TYPES))
        return package + sorted(STANDARD_TYPES)

    def service_names(self) -> list[str]:
        return sorted(self._services)


def resolve_short_name(name: str, full_names: list[str], profile: str) -> str:
    """The one full name among `full_names` whose type name is `name`."""
    matches = sorted({full for full in full_names if full.rpartition("/")[2] == name})
    if len(matches) == 1:
        return matches[0]
    if matches:
        raise UnknownTypeError(f"{name!r} is ambiguous in {profile}: {', '.join(matches)}")
    similar = sorted(
        {full for full in full_names if name.lower() in full.rpartition("/")[2].lower()}
    )
    hint = f"; did you mean {', '.join(similar)}?" if similar else ""
    raise UnknownTypeError(f"no message or service type {name!r} in {profile}{hint}")


@overload
def get_profile() -> morai_26_r1.ReleaseProfile: ...
@overload
def get_profile(name: Literal["26.r1"]) -> morai_26_r1.ReleaseProfile: ...  # type: ignore[overload-overlap]
@overload
def get_profile(name: Literal["24.r2"]) -> morai_24_r2.ReleaseProfile: ...  # type: ignore[overload-overlap]
@overload
def get_profile(name: Literal["2021.08"]) -> morai_2021_08.ReleaseProfile: ...  # type: ignore[overload-overlap]
@overload
def get_profile(name: str) -> Profile: ...
def get_profile(
    name: str = DEFAULT_PROFILE,
) -> (
    Profile | morai_26_r1.ReleaseProfile | morai_24_r2.ReleaseProfile | morai_2021_08.ReleaseProfile
):
    """The profile `name`, built once per process; a release named literally is seen
    through its typed view (its `message` and `service` know each type's fields)."""
    return built_profile(name)


@functools.cache
def built_profile(name: str) -> Profile:
    return Profile(name)
