"""How a message or service type is described to the transport: name, md5sum, definition."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol


class MessageTypeInfo(Protocol):
    """What TCPROS needs of a message type (``egosim.msgs`` MessageType satisfies it)."""

    @property
    def name(self) -> str: ...

    @property
    def md5sum(self) -> str: ...

    @property
    def definition(self) -> str: ...


class ServiceTypeInfo(Protocol):
    """What TCPROS needs of a service type (``egosim.msgs`` ServiceType satisfies it)."""

    @property
    def name(self) -> str: ...

    @property
    def md5sum(self) -> str: ...

    @property
    def request(self) -> MessageTypeInfo: ...

    @property
    def response(self) -> MessageTypeInfo: ...


@dataclass(frozen=True)
class TopicType:
    """A plain message type description; ``md5sum='*'`` and ``name='*'`` accept any type."""

    name: str
    md5sum: str
    definition: str = ""


@dataclass(frozen=True)
class ServiceType:
    """A plain service type description."""

    name: str
    md5sum: str
    request: TopicType
    response: TopicType


ANY_TYPE = TopicType("*", "*", "")
