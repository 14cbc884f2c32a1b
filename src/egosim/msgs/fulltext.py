"""Definition texts and md5 texts as genmsg computes them.

rosbags computes a message's md5 but not the md5 *text* a service md5 is built
from, nor the full text with the original file's own lines; both follow
genmsg (gentools.compute_md5_text / compute_full_text) exactly.
"""

from __future__ import annotations

from collections.abc import Callable
from hashlib import md5
from typing import Any

from rosbags.interfaces import Nodetype
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
        nodetype, args = element_desc(desc)
        if nodetype == Nodetype.NAME and args not in BUILTIN_TIME_TYPES and args not in depends:
            depends.append(args)
    return depends


def element_desc(desc: tuple[Any, Any]) -> tuple[Any, Any]:
    """The description of a field's element type (the field's own, for non-arrays)."""
    nodetype, args = desc
    return args[0] if nodetype in (Nodetype.ARRAY, Nodetype.SEQUENCE) else desc


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
        nodetype, args = element_desc(desc)
        if nodetype == Nodetype.BASE:
            lines.append(f"{args[0]}{suffix} {name}")
        elif args in BUILTIN_TIME_TYPES:
            lines.append(f"{BUILTIN_TIME_TYPES[args]}{suffix} {name}")
        else:
            lines.append(f"{store.generate_msgdef(args)[1]} {name}")
    return "\n".join(lines)


def service_md5(store: Typestore, request: str, response: str) -> str:
    """The md5sum of a service: over the request's and the response's md5 texts."""
    text = md5_text(store, request) + md5_text(store, response)
    return md5(text.encode()).hexdigest()
