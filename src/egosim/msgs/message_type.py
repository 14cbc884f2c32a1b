"""One message or service type: its identity on the wire, construction and (de)serialisation."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Generic, Protocol, TypeVar, cast

from rosbags.interfaces.typing import FieldDesc
from rosbags.typesys.msg import normalize_msgtype
from rosbags.typesys.store import Typestore

from .defaults import DefaultsPlan, defaults_plan
from .errors import SerializationError
from .packing import (
    FlatPacker,
    Packer,
    StampedPacker,
    flat_packer,
    packer,
    restamped,
    stamped_packer,
)
from .values import FieldValue

M = TypeVar("M")
"""A message's type: a Protocol of egosim.msgs.typed, or object for a type named at run time."""
M_co = TypeVar("M_co", covariant=True)
Request = TypeVar("Request")
Response = TypeVar("Response")


class MessageMaker(Protocol[M_co]):
    """Makes a message from the fields given by name, every other field at its default."""

    def __call__(self, **values: FieldValue) -> M_co: ...


class TypedMessageType(Protocol[M]):
    """What the typed view of a message type (egosim.msgs.typed's `<Name>Type`) has of a
    `MessageType[M]`; each view adds a `new` whose keywords are the type's fields."""

    name: str
    md5sum: str
    definition: str
    store: Typestore
    store_name: str
    make: type[M]

    @property
    def fields(self) -> list[tuple[str, FieldDesc]]: ...

    def serialize(self, message: M | bytes) -> bytes: ...

    def serialize_stamped(self, message: M, seq: int, stamp_ns: int) -> bytes: ...

    def flat(self, first: str | None = None, last: str | None = None) -> FlatPacker: ...

    def deserialize(self, data: bytes | memoryview) -> M: ...


@dataclass(eq=False)
class MessageType(Generic[M]):
    """One ROS 1 message type: its identity on the wire, construction and (de)serialisation.

    `M` only tells the type checker what the messages hold (egosim.msgs.typed): at run
    time they are rosbags' classes. A type looked up by a name written in the code is
    seen through its typed view, whose `new` and `make` the type checker checks; one
    named at run time checks its field names when a message is made and its values
    when it is serialised."""

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
    pack_stamped: StampedPacker | None = field(init=False, repr=False)
    """Its stamped packer, for a type that leads with a std_msgs/Header (packing.py)."""
    new: MessageMaker[M] = field(init=False, repr=False)
    """A message with the fields given set and every other field at its ROS default."""
    make: type[M] = field(init=False, repr=False)
    """The type's class itself: a message from every one of its fields (none defaulted),
    the cheapest way to build one, for rows that build many."""

    def __post_init__(self) -> None:
        self.store_name = normalize_msgtype(self.name)
        self.defaults = defaults_plan(self.store, self.store_name)
        self.pack = packer(self.store, self.store_name)
        self.pack_stamped = stamped_packer(self.store, self.store_name)
        # the class registered for store_name, the one `M` describes
        self.new = cast("MessageMaker[M]", self.defaults.new)
        self.make = cast("type[M]", self.defaults.message_class)

    @property
    def fields(self) -> list[tuple[str, FieldDesc]]:
        """(name, rosbags field description) pairs, in wire order."""
        return list(self.store.fielddefs[self.store_name][1])

    def serialize(self, message: M | bytes) -> bytes:
        """`message`'s ROS 1 bytes; a message given as its bytes already (a row that
        writes its own) is those bytes."""
        if type(message) is bytes:
            return message
        data = self.pack(message)
        if data is not None:
            return data
        try:
            return bytes(self.store.serialize_ros1(message, self.store_name))
        except Exception as exc:
            raise SerializationError(f"cannot serialize {self.name}: {exc}") from exc

    def serialize_stamped(self, message: M, seq: int, stamp_ns: int) -> bytes:
        """`message`'s bytes with `seq` and the stamp `stamp_ns` (ns) in its header, which
        is not read for them; for a type whose first field is its std_msgs/Header."""
        sec, nanosec = divmod(stamp_ns, 1_000_000_000)
        if self.pack_stamped is not None:
            data = self.pack_stamped(message, seq, sec, nanosec)
            if data is not None:
                return data
        return restamped(self.serialize(message), seq, sec, nanosec)

    def flat(self, first: str | None = None, last: str | None = None) -> FlatPacker:
        """The type's flat packer, of its leaves from `first` to `last` (packing.py)."""
        return flat_packer(self.store, self.store_name, first, last)

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
