"""Types as `rosmsg show` / `rossrv show` print them: constants, then fields, nested types
expanded beneath their field, two spaces deeper."""

from __future__ import annotations

from rosbags.interfaces import Nodetype
from rosbags.interfaces.typing import FieldDesc
from rosbags.typesys.msg import denormalize_msgtype
from rosbags.typesys.store import Typestore

from .definitions import SERVICE_SEPARATOR
from .fulltext import BUILTIN_TIME_TYPES, element_desc
from .message_type import MessageType, ServiceType

INDENT = "  "


def type_text(desc: FieldDesc) -> str:
    """A field's type as a .msg file spells it (`float64[9]`, `std_msgs/Header`, `time`)."""
    suffix = ""
    if desc[0] == Nodetype.ARRAY:
        suffix = f"[{desc[1][1]}]"
    elif desc[0] == Nodetype.SEQUENCE:
        suffix = "[]"
    element = element_desc(desc)
    if element[0] == Nodetype.BASE:
        return f"{element[1][0]}{suffix}"
    return f"{BUILTIN_TIME_TYPES.get(element[1]) or denormalize_msgtype(element[1])}{suffix}"


def field_lines(store: Typestore, store_name: str, indent: str = "") -> list[str]:
    constants, fields = store.fielddefs[store_name]
    lines = [f"{indent}{typ} {name}={value}" for name, typ, value in constants]
    for name, desc in fields:
        lines.append(f"{indent}{type_text(desc)} {name}")
        element = element_desc(desc)
        if element[0] == Nodetype.NAME and element[1] not in BUILTIN_TIME_TYPES:
            lines += field_lines(store, element[1], indent + INDENT)
    return lines


def show_message(message: MessageType[object]) -> str:
    """What `rosmsg show` prints for `message`."""
    return "".join(f"{line}\n" for line in field_lines(message.store, message.store_name))


def show_service(service: ServiceType[object, object]) -> str:
    """What `rossrv show` prints for `service`: the request, `---`, the response."""
    request = show_message(service.request)
    response = show_message(service.response)
    return f"{request}{SERVICE_SEPARATOR}\n{response}"
