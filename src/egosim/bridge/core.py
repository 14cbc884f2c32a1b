"""Binds the enabled rows of the protocol table to the ROS node.

Each row's behaviour is a handler (bridge/bindings.py): a builder for
publishers, a message handler for subscribers, a request handler for
services (bridge/receivers.py: each with the type it takes); every handler gets the
context and its effective row (the name in use, under its namespace). Builders run
on the loop thread in the tick pipeline's publish stage; received messages and
service requests are decoded on the transport's threads and applied on the loop
thread through the loop's inbox.
"""

from __future__ import annotations

import dataclasses
import logging
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Protocol, TypeVar

from ..logthrottle import LogThrottle
from ..msgs import MessageType, MsgsError, TypedMessageType, get_profile
from ..msgs.packing import restamped
from ..ros1 import (
    BadRequestError,
    ConnectionRefusedByPeerError,
    Node,
    Publisher,
    ServiceServer,
    Subscriber,
    Variants,
)
from ..ros1.types import TopicType
from .context import BridgeContext
from .protocol.messages import time_msg
from .protocol.network import NetworkSettings
from .protocol.releases import (
    CANONICAL_PROFILE,
    Release,
    ServiceRelease,
    canonical,
    convert,
    release_for_md5,
    releases_of,
    service_release_for_md5,
    service_releases_of,
)
from .protocol.table import Direction, Row
from .rate_schedule import RateSchedule
from .receivers import Receiver, handler

if TYPE_CHECKING:
    from ..msgs.typed import standard
    from .protocol.releases import CanonicalProfile

log = logging.getLogger(__name__)
throttle = LogThrottle(log)

T = TypeVar("T")
M = TypeVar("M")

# (context, row) -> a message, several (a list or tuple), or None when there is nothing to
# say; each builder declares its row's message type (egosim.msgs.typed). A message may be
# given as its bytes in the canonical release (`bytes`), written by the row itself (the
# busiest rows: their fields worked out in bulk and packed without building a message);
# a message that leads with its header then has seq and stamp zero, for the outlet to set.
Builder = Callable[[BridgeContext, Row], object]
# (topic, message type, serialized bytes, stamp ns): sees every message sent or received
Tap = Callable[[str, MessageType[object], bytes, int], None]
# (context, row): what a publishing row due with no subscriber and no tap does instead of
# being built
Unheard = Callable[[BridgeContext, Row], None]
# (bridge, row): advertises the topics a row stands for (Bridge.advertise); returns what
# withdraws them
Opener = Callable[["Bridge", Row], Callable[[], None]]


class Inbox(Protocol):
    """Hands work to the simulation loop's thread (app/inbox.py)."""

    def post(self, work: Callable[[], object]) -> None: ...

    def call(self, work: Callable[[], T], timeout: float | None = ...) -> T: ...


@dataclass(frozen=True)
class Handlers:
    publishers: dict[str, Builder] = field(default_factory=dict)
    subscribers: dict[str, Receiver[None]] = field(default_factory=dict)
    services: dict[str, Receiver[object]] = field(default_factory=dict)  # -> the response
    # (service row key, release) -> what to do with a request field that only that
    # release has (the request as the client sent it), before the row's handler answers
    release_adapters: dict[tuple[str, str], Receiver[None]] = field(default_factory=dict)
    # publishing rows that open topics of their own, given the bridge and the effective
    # row (the camera row: one topic per configured camera name)
    openers: dict[str, Opener] = field(default_factory=dict)
    # publisher row key -> the row's static part: built once, before the row's first
    # message, and latched (every subscriber gets it first; later messages never replace it)
    latched: dict[str, Builder] = field(default_factory=dict)
    # publisher row key -> what a due message nobody listens to still does (it is not
    # built): a row that reports the events since its previous message marks them
    # reported, or the next subscriber's first message would bring events long past
    unheard: dict[str, Unheard] = field(default_factory=dict)

    def __contains__(self, key: str) -> bool:
        return (
            key in self.publishers
            or key in self.subscribers
            or key in self.services
            or key in self.openers
        )


@dataclass
class Outlet:
    """A publishing row: when it is next due and how many headers it has stamped."""

    row: Row
    publisher: Publisher
    message_type: MessageType[object]  # the canonical release's, which builders fill
    releases: tuple[Release, ...]  # every release a subscriber may ask for, default first
    build: Builder
    schedule: RateSchedule
    seq: int = 0
    static: Builder | None = None  # Handlers.latched's builder, until it has run
    leads_with_header: bool = field(init=False)
    """Its messages start with their header (every MORAI message with one does)."""

    def __post_init__(self) -> None:
        first = dataclasses.fields(self.message_type.defaults.message_class)[0]
        self.leads_with_header = first.name == "header"

    def variant(self, message: object, md5sum: str) -> bytes:
        """`message` serialized in the release a subscriber negotiated by `md5sum`."""
        release = release_for_md5(self.releases, md5sum)
        assert release is not None  # the negotiator accepted only these md5sums
        return release.message_type.serialize(
            convert(message, self.message_type, release.message_type)
        )


class Bridge:
    """The rows of the protocol table bound to a ROS node; `open` binds them to a context."""

    def __init__(
        self,
        node: Node,
        settings: NetworkSettings,
        handlers: Handlers,
        inbox: Inbox,
        default_release: str = CANONICAL_PROFILE,
    ) -> None:
        self.node = node
        self.default_release = default_release
        self.settings = settings
        self.handlers = handlers
        self.inbox = inbox
        self.outlets: list[Outlet] = []
        self.taps: list[Tap] = []
        self._context: BridgeContext | None = None
        # What unbinds each row of the table that is bound (not namespaced copies).
        self._unbinders: dict[str, Callable[[], None]] = {}

    @property
    def context(self) -> BridgeContext:
        if self._context is None:
            raise RuntimeError("the bridge is not open")
        return self._context

    def open(self, context: BridgeContext) -> None:
        """Advertise, subscribe and serve every enabled row, handled with `context` (all
        registered with the master in one request)."""
        self._context = context
        with self.node.registering_together():
            for row in self.settings.enabled_rows():
                self._bind(row)

    def apply_settings(self, settings: NetworkSettings) -> list[str]:
        """Make `settings` the table in force, changing only the rows that changed: a
        renamed or disabled row is withdrawn, a new or renamed one opened, a re-rated one
        keeps its connections and publishes at its new rate; clients of unchanged rows
        keep theirs. What changed, for the log."""
        before = {row.key: row for row in self.settings.enabled_rows()}
        after = {row.key: row for row in settings.enabled_rows()}
        changes = []
        for key, row in before.items():
            if key not in after or after[key].name != row.name:
                self._unbinders.pop(key)()
                changes.append(f"{row.name} withdrawn")
        self.settings = settings
        for key, row in after.items():
            old = before.get(key)
            if old is None or old.name != row.name:
                self._bind(row)
                changes.append(f"{row.name} opened")
            elif old.rate_hz != row.rate_hz:
                if key in self.handlers.openers:  # several topics: opened again at the rate
                    self._unbinders.pop(key)()
                    self._bind(row)
                else:
                    outlet = next(o for o in self.outlets if o.row.key == key and o.row == old)
                    outlet.row, outlet.schedule = row, RateSchedule(row.rate_hz)
                changes.append(f"{row.name} at {row.rate_hz:g} Hz")
        return changes

    def _bind(self, row: Row) -> None:
        if row.key in self.handlers.openers:
            self._unbinders[row.key] = self.handlers.openers[row.key](self, row)
        elif row.direction is Direction.PUBLISH:
            self._unbinders[row.key] = self.advertise(row, self.handlers.publishers[row.key])
        elif row.direction is Direction.SUBSCRIBE:
            self._unbinders[row.key] = self._subscribe(
                row, self.handlers.subscribers[row.key]
            ).close
        else:
            self._unbinders[row.key] = self._serve(row).close

    def _withdraw(self, outlet: Outlet) -> None:
        self.outlets.remove(outlet)
        outlet.publisher.close()

    def open_publisher(self, key: str, namespace: str, build: Builder) -> Callable[[], None] | None:
        """Advertise the publishing row `key` under `namespace` at run time (loop thread),
        built by `build`, e.g. the status of an ego that appears; returns what withdraws
        it, or None when the network settings disable the row."""
        row = self._namespaced(key, namespace, Direction.PUBLISH)
        return None if row is None else self.advertise(row, build)

    def open_subscriber(
        self,
        key: str,
        namespace: str,
        takes: Callable[[CanonicalProfile], TypedMessageType[M]],
        handle: Callable[[BridgeContext, Row, M], None],
    ) -> Callable[[], None] | None:
        """Subscribe the row `key` under `namespace` at run time (loop thread), its
        messages (of the type `takes` names) handled by `handle`; returns what closes it,
        or None when the network settings disable the row."""
        row = self._namespaced(key, namespace, Direction.SUBSCRIBE)
        return None if row is None else self._subscribe(row, handler(takes, handle)).close

    def _namespaced(self, key: str, namespace: str, direction: Direction) -> Row | None:
        """The effective row `key` under `namespace`; None when it is disabled."""
        row = self.settings.row(key)
        if row.direction is not direction:
            raise ValueError(
                f"{row.name} ({row.direction.value}) is not opened as {direction.value}"
            )
        if not row.enabled:
            return None
        return replace(row, name=f"{namespace.rstrip('/')}/{row.name.lstrip('/~')}")

    def advertise(self, row: Row, build: Builder) -> Callable[[], None]:
        """Advertise a publishing row (of the table, namespaced, or an opener's); returns
        what withdraws it."""
        outlet = self._advertise(row, build)
        return lambda: self._withdraw(outlet)

    def publish_due(self, now: float) -> None:
        """Build and publish every outlet whose period has elapsed at loop time `now` (s)."""
        with self.context.readings:
            for outlet in self.outlets:
                if outlet.schedule.take(now):
                    self.publish(outlet)

    def publish(self, outlet: Outlet) -> None:
        if not self.taps and outlet.publisher.num_subscribers == 0:
            unheard = self.handlers.unheard.get(outlet.row.key)
            if unheard is not None:
                unheard(self.context, outlet.row)
            return
        if outlet.static is not None:
            static, outlet.static = outlet.static(self.context, outlet.row), None
            if static is not None:
                (variant,) = self._variants(outlet, static)
                outlet.publisher.latch_first(variant)
                outlet.publisher.publish_many((variant,))
        built = outlet.build(self.context, outlet.row)
        if built is None:
            return
        # A row's messages of one step (e.g. every intersection's status) go out together.
        outlet.publisher.publish_many(self._variants(outlet, built))

    def _variants(self, outlet: Outlet, built: object) -> list[Variants]:
        """The built message(s), stamped with the row's header sequence and the tick's
        stamp, serialised (other releases lazily), and tapped."""
        messages = built if isinstance(built, (list, tuple)) else (built,)
        message_type = outlet.message_type
        taps = self.taps
        # The stamp is read after the build, as the first message is packed: the build
        # stays out of the time between a tick's stamp (the first one read, in real
        # time) and its first send. Every message of a tick has the same one.
        stamp_ns = self.context.stamp_ns() if outlet.leads_with_header or taps else 0
        sec, nanosec = divmod(stamp_ns, 1_000_000_000)
        variants: list[Variants] = []
        for message in messages:
            if outlet.leads_with_header:
                seq = outlet.seq
                outlet.seq = seq + 1
                if type(message) is bytes:
                    data = restamped(message, seq, sec, nanosec)
                    variants.append(self._serialized(outlet, None, data))
                else:
                    data = message_type.serialize_stamped(message, seq, stamp_ns)
                    header = message.header
                    header.seq = seq
                    variants.append(self._serialized(outlet, message, data, header, stamp_ns))
            elif type(message) is bytes:
                data = message
                variants.append(self._serialized(outlet, None, data))
            else:
                header = getattr(message, "header", None)
                if header is not None:
                    header.seq = outlet.seq
                    outlet.seq += 1
                data = message_type.serialize(message)
                variants.append(self._serialized(outlet, message, data))
            for tap in taps:
                tap(outlet.row.name, message_type, data, stamp_ns)
        return variants

    def _serialized(
        self,
        outlet: Outlet,
        message: object,
        data: bytes,
        stamped_header: standard.Header | None = None,
        stamp_ns: int = 0,
    ) -> Callable[[str], bytes]:
        """The message in the release a subscriber's md5sum names: `data` for the
        canonical one, converted and serialised on demand for another, from `message`, or
        from `data` itself for a row that wrote its bytes (`message` None). A header whose
        stamp went into `data`'s bytes only (`stamped_header`) is given it first."""
        profile = self.context.profile
        canonical_md5 = outlet.message_type.md5sum

        def serialize(md5sum: str) -> bytes:
            if md5sum == canonical_md5:
                return data
            if stamped_header is not None:
                stamped_header.stamp = time_msg(profile, stamp_ns)
            read = outlet.message_type.deserialize(data) if message is None else message
            return outlet.variant(read, md5sum)

        return serialize

    def _advertise(self, row: Row, build: Builder) -> Outlet:
        releases = releases_of(row.type_name, self.default_release)
        static = self.handlers.latched.get(row.key)
        publisher = self.node.advertise(
            row.name,
            releases[0].message_type,
            latch=static is not None,
            negotiate=negotiator(row.name, releases),
        )
        outlet = Outlet(
            row,
            publisher,
            canonical(row.type_name),
            releases,
            build,
            RateSchedule(row.rate_hz),
            static=static,
        )
        self.outlets.append(outlet)
        return outlet

    def _subscribe(self, row: Row, receiver: Receiver[None]) -> Subscriber:
        """Subscribe asking for any md5sum; decode each publisher's release by its md5sum."""
        releases = releases_of(row.type_name, self.default_release)

        def received(data: bytes, header: Mapping[str, str]) -> None:
            caller = header.get("callerid", "?")
            release = release_for_md5(releases, header.get("md5sum", ""))
            if release is None:
                throttle.log(
                    logging.ERROR,
                    (row.name, caller, "md5sum"),
                    "%s from %s: md5sum %s is no release of %s; message dropped",
                    row.name,
                    caller,
                    header.get("md5sum"),
                    row.type_name,
                )
                return
            sent_type = release.message_type
            try:
                handle = receiver.receive(self.context, row, sent_type.deserialize(data), sent_type)
            except MsgsError as exc:
                throttle.log(
                    logging.ERROR,
                    (row.name, caller, "undecodable"),
                    "%s from %s: message dropped: %s",
                    row.name,
                    caller,
                    exc,
                )
                return
            # the clock itself: the tick's readings are the loop thread's
            stamp_ns = self.context.clock.now_ns()
            for tap in self.taps:
                tap(row.name, sent_type, data, stamp_ns)
            self.inbox.post(handle)

        any_release = TopicType(row.type_name, "*", releases[0].message_type.definition)
        return self.node.subscribe(row.name, any_release, received)

    def _serve(self, row: Row) -> ServiceServer:
        """Serve the row to clients of any release, each answered in its own."""
        releases = service_releases_of(row.type_name, self.default_release)
        canonical_type = get_profile(CANONICAL_PROFILE).service(row.type_name)
        receiver = self.handlers.services[row.key]

        def release_of(header: Mapping[str, str]) -> ServiceRelease:
            release = service_release_for_md5(releases, header.get("md5sum", "*"))
            if release is None:
                accepted = [(r.service_type.md5sum, r.profile_name) for r in releases]
                raise refusal(row.name, row.type_name, header.get("md5sum"), accepted)
            return release

        def serve(data: bytes, header: Mapping[str, str]) -> bytes:
            release = release_of(header)
            served = release.service_type
            try:
                sent = served.request.deserialize(data)
            except MsgsError as exc:
                raise BadRequestError(f"undecodable {served.request.name}: {exc}") from None
            adapter = self.handlers.release_adapters.get((row.key, release.profile_name))
            adapt = (
                None
                if adapter is None
                else adapter.receive(self.context, row, sent, served.request)
            )
            handle = receiver.receive(self.context, row, sent, served.request)

            def answer() -> object:
                if adapt is not None:
                    adapt()
                return handle()

            response = self.inbox.call(answer)
            return served.response.serialize(
                convert(response, canonical_type.response, served.response)
            )

        return self.node.advertise_service(
            row.name,
            releases[0].service_type,
            serve,
            negotiate=lambda header: release_of(header).service_type,
        )


def negotiator(
    topic: str, releases: tuple[Release, ...]
) -> Callable[[Mapping[str, str]], MessageType[object]]:
    """Picks the release a subscriber's md5sum asks for (`*`: the default one)."""

    def negotiate(header: Mapping[str, str]) -> MessageType[object]:
        wanted = header.get("md5sum", "*")
        if wanted == "*":
            return releases[0].message_type
        release = release_for_md5(releases, wanted)
        if release is None:
            accepted = [(r.message_type.md5sum, r.profile_name) for r in releases]
            raise refusal(topic, releases[0].message_type.name, wanted, accepted)
        return release.message_type

    return negotiate


def refusal(
    name: str, type_name: str, md5sum: str | None, accepted: list[tuple[str, str]]
) -> ConnectionRefusedByPeerError:
    """The error a peer asking for an unknown release gets: what egosim would accept."""
    choices = ", ".join(f"{md5} ({release})" for md5, release in accepted)
    return ConnectionRefusedByPeerError(
        f"{name}: md5sum {md5sum} is no morai_msgs release of {type_name}; accepted: {choices}"
    )
