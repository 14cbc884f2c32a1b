"""One message or service type: its identity on the wire, construction and (de)serialisation."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Generic, TypeVar, cast

from rosbags.typesys.msg import normalize_msgtype
from rosbags.typesys.store import Typestore

from .defaults import DefaultsPlan, defaults_plan
from .errors import SerializationError
from .packing import Packer, packer

M = TypeVar("M")
"""A message's type: a Protocol of egosim.msgs.typed, or Any for a type named at run time."""
Request = TypeVar("Request")
Response = TypeVar("Response")


@dataclass(eq=False)
class MessageType(Generic[M]):
    """One ROS 1 message type: its identity on the wire and its (de)serialisation.

    `M` only tells the type checker what the messages hold (egosim.msgs.typed): at run
    time they are rosbags' classes."""

    name: str
    md5sum: str
    definition: str
    store: Typestore = field(repr=False)
    store_name: str = field(init=False, repr=False)
    """The name in rosbags' store (`pkg/msg/Name`), worked out once: builders need it for
    every message they make."""
    defaults: DefaultsPlan = field(init=False, repr=False)
    pack: Packer = field(init=False, repr=False)
    """The type's precompiled serialiser, tried first (packing.py)."""

    def __post_init__(self) -> None:
        self.store_name = normalize_msgtype(self.name)
        self.defaults = defaults_plan(self.store, self.store_name)
        self.pack = packer(self.store, self.store_name)

    @property
    def fields(self) -> list[tuple[str, Any]]:
        """(name, rosbags field description) pairs, in wire order."""
        return list(self.store.fielddefs[self.store_name][1])

    def new(self, **values: Any) -> M:
        """A message with `values` set and every other field at its ROS default."""
        message: M = self.defaults.new(values)
        return message

    def make(self, **fields: Any) -> M:
        """A message from every one of its fields (none defaulted): the cheapest way to
        build one, for rows that build many."""
        message: M = self.defaults.message_class(**fields)
        return message

    def serialize(self, message: M) -> bytes:
        data = self.pack(message)
        if data is not None:
            return data
        try:
            return bytes(self.store.serialize_ros1(message, self.store_name))
        except Exception as exc:
            raise SerializationError(f"cannot serialize {self.name}: {exc}") from exc

    def deserialize(self, data: bytes | memoryview) -> M:
        try:
            # rosbags builds the class registered for store_name, the one `M` describes
            return cast(M, self.store.deserialize_ros1(data, self.store_name))
        except Exception as exc:
            raise SerializationError(
                f"cannot deserialize {len(data)} bytes as {self.name}: {exc}"
            ) from exc


@dataclass(frozen=True, eq=False)
class ServiceType(Generic[Request, Response]):
    """One ROS 1 service type: its md5 and its request and response messages."""

    name: str
    md5sum: str
    request: MessageType[Request]
    response: MessageType[Response]
    definition: str  # the .srv text, as `rossrv show` prints it
