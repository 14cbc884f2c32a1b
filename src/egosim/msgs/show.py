"""Types as `rosmsg show` / `rossrv show` print them: constants, then fields, nested types
expanded beneath their field, two spaces deeper."""

from __future__ import annotations

from typing import Any

from rosbags.interfaces import Nodetype
from rosbags.typesys.msg import denormalize_msgtype
from rosbags.typesys.store import Typestore

from .definitions import SERVICE_SEPARATOR
from .fulltext import BUILTIN_TIME_TYPES, element_desc
from .message_type import MessageType, ServiceType

INDENT = "  "


def type_text(desc: tuple[Any, Any]) -> str:
    """A field's type as a .msg file spells it (`float64[9]`, `std_msgs/Header`, `time`)."""
    suffix = ""
    if desc[0] == Nodetype.ARRAY:
        suffix = f"[{desc[1][1]}]"
    elif desc[0] == Nodetype.SEQUENCE:
        suffix = "[]"
    nodetype, args = element_desc(desc)
    if nodetype == Nodetype.BASE:
        return f"{args[0]}{suffix}"
    return f"{BUILTIN_TIME_TYPES.get(args) or denormalize_msgtype(args)}{suffix}"


def field_lines(store: Typestore, store_name: str, indent: str = "") -> list[str]:
    constants, fields = store.fielddefs[store_name]
    lines = [f"{indent}{typ} {name}={value}" for name, typ, value in constants]
    for name, desc in fields:
        lines.append(f"{indent}{type_text(desc)} {name}")
        nodetype, args = element_desc(desc)
        if nodetype == Nodetype.NAME and args not in BUILTIN_TIME_TYPES:
            lines += field_lines(store, args, indent + INDENT)
    return lines


def show_message(message: MessageType[Any]) -> str:
    """What `rosmsg show` prints for `message`."""
    return "".join(f"{line}\n" for line in field_lines(message.store, message.store_name))


def show_service(service: ServiceType[Any, Any]) -> str:
    """What `rossrv show` prints for `service`: the request, `---`, the response."""
    request = show_message(service.request)
    response = show_message(service.response)
    return f"{request}{SERVICE_SEPARATOR}\n{response}"
