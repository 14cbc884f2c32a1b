"""ROS 1 bytes of a message through a layout compiled once per type and release.

rosbags' serialiser packs every primitive field with a call of its own and walks the
message twice (its size, then its bytes). Here each type's whole tree is unrolled into
one generated function: every run of fixed-size fields, across nested messages and
including the length prefixes of the strings and sequences that end it, is one
`Struct.pack`; numeric arrays go out as their buffers. The bytes are those of rosbags:
whatever a layout does not take as it is (a numeric array of another dtype, byte order
or shape, an array of the wrong length, a value struct refuses) makes the packer
return None, and the caller serialises that message the generic way, which gives
rosbags' bytes or its error.
"""

from __future__ import annotations

import functools
import struct
from collections.abc import Callable
from typing import cast

import numpy as np
from rosbags.interfaces import Nodetype
from rosbags.interfaces.typing import BaseDesc, FieldDesc, NameDesc
from rosbags.typesys.store import Typestore

Packer = Callable[[object], bytes | None]
"""A message's ROS 1 bytes, or None when its layout does not take it as it is (any
object: whatever is not a message of the type is not taken)."""

FORMATS = {
    "bool": "?",
    "byte": "b",
    "char": "B",
    "int8": "b",
    "uint8": "B",
    "int16": "h",
    "uint16": "H",
    "int32": "i",
    "uint32": "I",
    "int64": "q",
    "uint64": "Q",
    "float32": "f",
    "float64": "d",
}
"""struct codes of the ROS 1 base types (little-endian, unpadded under '<')."""

DTYPES = {name: np.dtype(f"<{code}") for name, code in FORMATS.items() if code != "?"} | {
    "bool": np.dtype(np.bool_)
}
"""The numpy dtype a numeric array of each base type must have to go out as its buffer."""

# rosbags' stand-in member of a message with no fields: not on the wire.
EMPTY_MEMBER = "structure_needs_at_least_one_member"


class _UnpackableError(Exception):
    """A value the layout does not take as it is: the generic serialiser decides."""


class _Writer:
    """Generates one packer's source: statements, struct runs and the names they use."""

    def __init__(self, store: Typestore) -> None:
        self.store = store
        self.lines: list[str] = []
        self.names: dict[str, object] = {
            "_UnpackableError": _UnpackableError,
            "_ndarray": np.ndarray,
        }
        self.run_format = ""
        self.run_values: list[str] = []
        self.counter = 0

    def fresh(self, stem: str) -> str:
        self.counter += 1
        return f"_{stem}{self.counter}"

    def emit(self, depth: int, line: str) -> None:
        self.lines.append("    " * depth + line)

    def add(self, code: str, value: str) -> None:
        self.run_format += code
        self.run_values.append(value)

    def flush(self, depth: int) -> None:
        """End the struct run under way: one pack of its values."""
        if not self.run_format:
            return
        pack = self.fresh("pack")
        self.names[pack] = struct.Struct(f"<{self.run_format}").pack
        self.emit(depth, f"_out({pack}({', '.join(self.run_values)}))")
        self.run_format, self.run_values = "", []

    def message(self, store_name: str, value: str, depth: int) -> None:
        for name, desc in self.store.fielddefs[store_name][1]:
            if name != EMPTY_MEMBER:
                self.field(desc, f"{value}.{name}", depth)

    def field(self, desc: FieldDesc, value: str, depth: int) -> None:
        if desc[0] == Nodetype.NAME:
            self.message(desc[1], value, depth)
        elif desc[0] == Nodetype.BASE:
            self.base(desc[1][0], value, depth)
        else:
            element, length = desc[1]
            self.array(element, value, depth, length if desc[0] == Nodetype.ARRAY else None)

    def base(self, typename: str, value: str, depth: int) -> None:
        if typename != "string":
            self.add(FORMATS[typename], value)
            return
        encoded = self.fresh("s")
        self.emit(depth, f"{encoded} = {value}.encode()")
        self.add("I", f"len({encoded})")
        self.flush(depth)
        self.emit(depth, f"_out({encoded})")

    def array(
        self, element: BaseDesc | NameDesc, value: str, depth: int, length: int | None
    ) -> None:
        """A fixed-length array (`length`) or a sequence (None) of one element type."""
        items = self.fresh("a")
        self.emit(depth, f"{items} = {value}")
        numeric = element[0] == Nodetype.BASE and element[1][0] != "string"
        if numeric:
            dtype = self.fresh("dtype")
            self.names[dtype] = DTYPES[element[1][0]]
            self.emit(
                depth,
                f"if type({items}) is not _ndarray or {items}.dtype != {dtype} "
                f"or {items}.ndim != 1 or not {items}.flags.c_contiguous: raise _UnpackableError",
            )
        if length is not None:
            self.emit(depth, f"if len({items}) != {length}: raise _UnpackableError")
        else:
            self.add("I", f"len({items})")
        if numeric:
            self.flush(depth)
            self.emit(depth, f"_out({items}.data)")
            return
        self.flush(depth)
        item = self.fresh("e")
        self.emit(depth, f"for {item} in {items}:")
        self.field(element, item, depth + 1)
        self.flush(depth + 1)


@functools.cache
def packer(store: Typestore, store_name: str) -> Packer:
    """The packer of `store_name` in `store` (one release's types), compiled on first use."""
    writer = _Writer(store)
    writer.message(store_name, "message", 1)
    writer.flush(1)
    body = writer.lines or ["    pass"]  # a message with no fields: no bytes
    source = "\n".join(
        [
            "def pack(message):",
            "    _parts = []",
            "    _out = _parts.append",
            "    try:",
            *("    " + line for line in body),
            "    except Exception:  # the generic serialiser gives the bytes or the error",
            "        return None",
            "    return b''.join(_parts)",
        ]
    )
    namespace = dict(writer.names)
    exec(compile(source, f"<packer of {store_name}>", "exec"), namespace)
    return cast(Packer, namespace["pack"])  # the `def pack` just executed
