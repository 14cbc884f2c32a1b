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

Two more forms are generated from the same layouts. A stamped packer takes a message
whose first field is its std_msgs/Header with the header's seq and stamp as arguments
of their own, so a message is stamped as it is packed, not copied to be stamped after.
A flat packer takes no message at all: each leaf of the type's tree (a base field, a
numeric array as its numpy array, a sequence or array of messages as its elements'
packed bytes) is one positional argument, in wire order, so a row that works out its
fields in bulk writes its bytes without building a message; a range of leaves packs
that part of the message alone (its bytes are the message's from its first leaf to its
last), for the parts a row keeps from one message to the next.
"""

from __future__ import annotations

import functools
import struct
from collections.abc import Callable
from dataclasses import dataclass
from typing import cast

import numpy as np
from rosbags.interfaces import Nodetype
from rosbags.interfaces.typing import BaseDesc, FieldDesc, NameDesc
from rosbags.typesys.store import Typestore

Packer = Callable[[object], bytes | None]
"""A message's ROS 1 bytes, or None when its layout does not take it as it is (any
object: whatever is not a message of the type is not taken)."""
StampedPacker = Callable[[object, int, int, int], bytes | None]
"""(message, seq, stamp sec, stamp nanosec) -> the message's ROS 1 bytes with that seq
and stamp in its header (its own are not read), or None as for a Packer."""

#: The leaves of a leading std_msgs/Header that a stamped packer takes as arguments.
_STAMP_LEAVES = {
    "message.header.seq": "_seq",
    "message.header.stamp.sec": "_sec",
    "message.header.stamp.nanosec": "_nanosec",
}
_MESSAGE = "message"
#: A std_msgs/Header's seq, stamp.sec and stamp.nanosec: the first 12 bytes of a message
#: that leads with its header.
_HEADER_START = struct.Struct("<III")

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


class _UnpackableError(ValueError):
    """A value the layout does not take as it is: the generic serialiser decides."""


@dataclass(frozen=True)
class FlatPacker:
    """The bytes of a type's leaves given one by one (see the module's docstring)."""

    leaves: tuple[str, ...]
    """The dotted path of each leaf it takes, in the order it takes them."""
    pack: Callable[..., bytes]
    """The leaves' bytes; raises (struct.error, TypeError, ValueError) on a value the
    layout does not take, as there is no message to hand to the generic serialiser."""


class _Writer:
    """Generates one packer's source: statements, struct runs and the names they use.

    `stamped`: the leading header's seq and stamp are arguments (_STAMP_LEAVES).
    `flat`: the message's leaves from `first` to `last` (dotted paths; None: the first,
    the last leaf) are the arguments, packed in order; the others are skipped."""

    def __init__(
        self,
        store: Typestore,
        *,
        stamped: bool = False,
        flat: bool = False,
        first: str | None = None,
        last: str | None = None,
    ) -> None:
        self.store = store
        self.stamped = stamped
        self.flat = flat
        self.first, self.last = first, last
        self.packing = first is None
        self.params: list[str] = []
        self.leaves: list[str] = []
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
            return
        leaf = self.leaf(value)
        if leaf is None:
            return
        if desc[0] == Nodetype.BASE:
            self.base(desc[1][0], leaf, depth)
        else:
            element, fixed_length = desc[1]
            length = fixed_length if desc[0] == Nodetype.ARRAY else None
            if self.flat and element[0] == Nodetype.NAME and value.startswith(_MESSAGE):
                self.packed_elements(leaf, depth, length)
            else:
                self.array(element, leaf, depth, length)

    def leaf(self, value: str) -> str | None:
        """What a leaf's value is read from: its attribute path, or the argument that
        gives it; None for a leaf outside a flat packer's range. Leaves of a sequence's
        elements (not under `message`) are read from the element."""
        if not value.startswith(f"{_MESSAGE}."):
            return value
        if self.stamped and value in _STAMP_LEAVES:
            return _STAMP_LEAVES[value]
        if not self.flat:
            return value
        path = value.removeprefix(f"{_MESSAGE}.")
        self.leaves.append(path)
        self.packing = self.packing or path == self.first
        if not self.packing:
            return None
        if path == self.last:
            self.packing = False
        param = f"_v{len(self.params)}"
        self.params.append(param)
        return param

    def packed_elements(self, items: str, depth: int, length: int | None) -> None:
        """A flat packer's sequence or array of messages: given as its elements' bytes."""
        if length is not None:
            self.emit(depth, f"if len({items}) != {length}: raise ValueError('{length} elements')")
        else:
            self.add("I", f"len({items})")
        self.flush(depth)
        self.emit(depth, f"_parts.extend({items})")

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
    return cast(Packer, _compiled(_Writer(store), store_name, [_MESSAGE]))


@functools.cache
def stamped_packer(store: Typestore, store_name: str) -> StampedPacker | None:
    """The stamped packer of `store_name` in `store`; None when the type does not lead
    with a std_msgs/Header."""
    fields = store.fielddefs[store_name][1]
    if not fields or fields[0][1] != (Nodetype.NAME, "std_msgs/msg/Header"):
        return None
    params = [_MESSAGE, *_STAMP_LEAVES.values()]
    return cast(StampedPacker, _compiled(_Writer(store, stamped=True), store_name, params))


@functools.cache
def flat_packer(
    store: Typestore, store_name: str, first: str | None = None, last: str | None = None
) -> FlatPacker:
    """The flat packer of `store_name` in `store`, of its leaves from `first` to `last`
    (dotted paths, e.g. "pose.position.x"; None: the first, the last)."""
    writer = _Writer(store, flat=True, first=first, last=last)
    pack = _compiled(writer, store_name)
    for end in (first, last):
        if end is not None and end not in writer.leaves:
            raise ValueError(f"{store_name} has no leaf {end!r}: {writer.leaves}")
    start = 0 if first is None else writer.leaves.index(first)
    leaves = tuple(writer.leaves[start : start + len(writer.params)])
    return FlatPacker(leaves, cast(Callable[..., bytes], pack))


def _compiled(
    writer: _Writer, store_name: str, params: list[str] | None = None
) -> Callable[..., object]:
    """The packing function `writer` generates for `store_name`, taking `params` (None:
    a flat packer's leaves). A packer of a message returns None when its layout refuses
    a value; a flat packer raises."""
    writer.message(store_name, _MESSAGE, 1)
    writer.flush(1)
    body = writer.lines or ["    pass"]  # a message with no fields: no bytes
    start = ["    _parts = []", "    _out = _parts.append"]
    end = ["    return b''.join(_parts)"]
    if params is None:
        lines = [f"def pack({', '.join(writer.params)}):", *start, *body, *end]
    else:
        lines = [
            f"def pack({', '.join(params)}):",
            *start,
            "    try:",
            *("    " + line for line in body),
            "    except Exception:  # the generic serialiser gives the bytes or the error",
            "        return None",
            *end,
        ]
    namespace = dict(writer.names)
    exec(compile("\n".join(lines), f"<packer of {store_name}>", "exec"), namespace)
    return cast(Callable[..., object], namespace["pack"])  # the `def pack` just executed


def restamped(data: bytes, seq: int, sec: int, nanosec: int) -> bytes:
    """`data`, the bytes of a message that leads with its std_msgs/Header, with that
    header's seq and stamp replaced."""
    return b"".join((_HEADER_START.pack(seq, sec, nanosec), memoryview(data)[_HEADER_START.size :]))
