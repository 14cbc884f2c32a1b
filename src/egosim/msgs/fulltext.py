"""Definition texts and md5 texts as genmsg computes them.

rosbags computes a message's md5 but not the md5 *text* a service md5 is built
from, nor the full text with the original file's own lines; both follow
genmsg (gentools.compute_md5_text / compute_full_text) exactly.
"""

from __future__ import annotations

from collections.abc import Callable
from hashlib import md5

from rosbags.interfaces import Nodetype
from rosbags.interfaces.typing import BaseDesc, FieldDesc, NameDesc
from rosbags.typesys.msg import denormalize_msgtype
from rosbags.typesys.store import Typestore

# ROS 1 built-ins that rosbags models as messages.
BUILTIN_TIME_TYPES = {
    "builtin_interfaces/msg/Time": "time",
    "builtin_interfaces/msg/Duration": "duration",
}
SEPARATOR = "=" * 80 + "\n"


def direct_depends(store: Typestore, store_name: str) -> list[str]:
    """Message types used by the fields of `store_name`, in field order."""
    depends: list[str] = []
    for _, desc in store.fielddefs[store_name][1]:
        element = element_desc(desc)
        if element[0] != Nodetype.NAME:
            continue
        if element[1] not in BUILTIN_TIME_TYPES and element[1] not in depends:
            depends.append(element[1])
    return depends


def element_desc(desc: FieldDesc) -> BaseDesc | NameDesc:
    """The description of a field's element type (the field's own, for non-arrays)."""
    if desc[0] == Nodetype.ARRAY or desc[0] == Nodetype.SEQUENCE:
        return desc[1][0]
    return desc


def all_depends(store: Typestore, store_name: str) -> list[str]:
    """Every nested message type, depth first, each once (genmsg's order)."""
    result: list[str] = []
    for dep in direct_depends(store, store_name):
        for name in (dep, *all_depends(store, dep)):
            if name not in result:
                result.append(name)
    return result


def full_text(store: Typestore, store_name: str, own_text: Callable[[str], str]) -> str:
    """The `message_definition` text a ROS 1 peer sends for `store_name`."""
    parts = [own_text(store_name), "\n"]
    for dep in all_depends(store, store_name):
        parts += [SEPARATOR, f"MSG: {denormalize_msgtype(dep)}\n", own_text(dep), "\n"]
    return "".join(parts)[:-1]


def md5_text(store: Typestore, store_name: str) -> str:
    """genmsg's md5 text: constants, then fields with nested types replaced by their md5."""
    constants, fields = store.fielddefs[store_name]
    lines = [f"{typ} {name}={value}" for name, typ, value in constants]
    for name, desc in fields:
        suffix = ""
        if desc[0] in (Nodetype.ARRAY, Nodetype.SEQUENCE):
            count = desc[1][1]
            suffix = f"[{count}]" if count else "[]"
        element = element_desc(desc)
        if element[0] == Nodetype.BASE:
            lines.append(f"{element[1][0]}{suffix} {name}")
        elif element[1] in BUILTIN_TIME_TYPES:
            lines.append(f"{BUILTIN_TIME_TYPES[element[1]]}{suffix} {name}")
        else:
            lines.append(f"{store.generate_msgdef(element[1])[1]} {name}")
    return "\n".join(lines)


def service_md5(store: Typestore, request: str, response: str) -> str:
    """The md5sum of a service: over the request's and the response's md5 texts."""
    text = md5_text(store, request) + md5_text(store, response)
    return md5(text.encode()).hexdigest()
