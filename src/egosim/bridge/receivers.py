"""What a subscribing or serving row does with what it receives, typed by its handler.

A row's handler declares the message or request it takes (a type of egosim.msgs.typed);
its `Handler` names that type in the canonical profile, so the type checker holds the
two together, and what each row's handler takes is its row's type in the table
(tests/bridge/test_network_settings.py checks every row). A message arrives decoded in
its sender's release and is converted into that type, then prepared on the transport's
thread (when the row has a preparer: reading a user's file, so the loop never waits on
it), then handled on the loop thread.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Generic, Protocol, TypeVar

from ..msgs import MessageType, TypedMessageType
from .context import BridgeContext
from .protocol.releases import convert
from .protocol.table import Row

if TYPE_CHECKING:
    from .protocol.releases import CanonicalProfile

M = TypeVar("M")
"""The message or request a handler takes (a type of egosim.msgs.typed)."""
P = TypeVar("P")
"""What a row's preparer makes of it (the message itself when the row has none)."""
R = TypeVar("R")
"""What the handler returns: None for a topic, the response for a service."""
R_co = TypeVar("R_co", covariant=True)


class Receiver(Protocol[R_co]):
    """A row's handling of what it receives, whatever its type: what the bridge holds."""

    def receive(
        self, context: BridgeContext, row: Row, sent: object, sent_type: MessageType[object]
    ) -> Callable[[], R_co]:
        """`sent`, a message of `sent_type` (its sender's release), in the handler's type
        and prepared (the transport's thread); what hands it to the handler (the loop's)."""
        ...


@dataclass(frozen=True)
class Handler(Generic[M, P, R]):
    """A row's handler with the type it takes and what prepares each message for it."""

    takes: Callable[[CanonicalProfile], TypedMessageType[M]]
    """The type of the messages or requests the handler takes, in the canonical profile
    (looked up when one arrives: the profile is built on first use, not on import)."""
    prepare: Callable[[BridgeContext, Row, M], P]
    handle: Callable[[BridgeContext, Row, P], R]

    def receive(
        self, context: BridgeContext, row: Row, sent: object, sent_type: MessageType[object]
    ) -> Callable[[], R]:
        prepared = self.prepare(context, row, convert(sent, sent_type, self.takes(context.profile)))
        return lambda: self.handle(context, row, prepared)


def handler(
    takes: Callable[[CanonicalProfile], TypedMessageType[M]],
    handle: Callable[[BridgeContext, Row, M], R],
) -> Handler[M, M, R]:
    """`handle` for each message or request of the type `takes` names, as it arrives."""
    return Handler(takes, _as_received, handle)


def prepared_handler(
    takes: Callable[[CanonicalProfile], TypedMessageType[M]],
    prepare: Callable[[BridgeContext, Row, M], P],
    handle: Callable[[BridgeContext, Row, P], R],
) -> Handler[M, P, R]:
    """`handle` for what `prepare` makes of each message or request of the type `takes`
    names, on the transport's thread."""
    return Handler(takes, prepare, handle)


def _as_received(context: BridgeContext, row: Row, message: M) -> M:
    return message
