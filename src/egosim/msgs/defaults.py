"""Default-valued messages: zeros, empty strings and empty arrays, as genpy builds them.

Builders make tens of thousands of messages a second, so how to make each type's
defaults is worked out once per type (a `DefaultsPlan`), not per message.
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from rosbags.interfaces import Nodetype
from rosbags.typesys.store import Typestore

NUMPY_DTYPES = {
    "bool": np.bool_,
    "byte": np.int8,
    "char": np.uint8,
    "int8": np.int8,
    "uint8": np.uint8,
    "int16": np.int16,
    "uint16": np.uint16,
    "int32": np.int32,
    "uint32": np.uint32,
    "int64": np.int64,
    "uint64": np.uint64,
    "float32": np.float32,
    "float64": np.float64,
}

Maker = Callable[[], Any]
"""Makes a fresh default value of one field."""


def default_base(typename: str) -> Any:
    if typename == "string":
        return ""
    if typename == "bool":
        return False
    if typename.startswith("float"):
        return 0.0
    return 0


@dataclass(frozen=True)
class DefaultsPlan:
    """How to make one message type with every field at its default."""

    store_name: str
    message_class: type
    field_names: frozenset[str]
    constants: dict[str, Any]
    """Defaults of the base-type fields: immutable, so every message may share them."""
    makers: tuple[tuple[str, Maker], ...]
    """The other fields (messages, lists, arrays): made afresh for each message, so no
    two messages ever share a mutable default."""

    def new(self, values: dict[str, Any]) -> Any:
        """A message with `values` set and every other field at its default."""
        if not values.keys() <= self.field_names:
            unknown = sorted(set(values) - self.field_names)
            raise TypeError(f"{self.store_name} has no field(s) {', '.join(unknown)}")
        if len(values) == len(self.field_names):  # every field given: no default to make
            return self.message_class(**values)
        fields = {**self.constants, **values}
        for name, make in self.makers:
            if name not in values:
                fields[name] = make()
        return self.message_class(**fields)

    def fresh(self) -> Any:
        """A message with every field at its default."""
        return self.message_class(**self.constants, **{name: make() for name, make in self.makers})


@functools.cache
def defaults_plan(store: Typestore, store_name: str) -> DefaultsPlan:
    """The plan of `store_name`, worked out on first use (a store's types never change once
    registered)."""
    fields = store.fielddefs[store_name][1]
    constants = {}
    makers = []
    for name, desc in fields:
        if desc[0] == Nodetype.BASE:
            constants[name] = default_base(desc[1][0])
        else:
            makers.append((name, field_maker(store, desc)))
    return DefaultsPlan(
        store_name=store_name,
        message_class=store.types[store_name],
        field_names=frozenset(name for name, _ in fields),
        constants=constants,
        makers=tuple(makers),
    )


def field_maker(store: Typestore, desc: tuple[Any, Any]) -> Maker:
    nodetype, args = desc
    if nodetype == Nodetype.BASE:
        return functools.partial(default_base, args[0])
    if nodetype == Nodetype.NAME:
        return defaults_plan(store, args).fresh
    (subtype, subargs), count = args
    is_numeric = subtype == Nodetype.BASE and subargs[0] != "string"
    if nodetype == Nodetype.SEQUENCE:
        return functools.partial(np.zeros, 0, NUMPY_DTYPES[subargs[0]]) if is_numeric else list
    if is_numeric:
        return functools.partial(np.zeros, count, NUMPY_DTYPES[subargs[0]])
    make_element = field_maker(store, (subtype, subargs))
    return lambda: [make_element() for _ in range(count)]


def default_message(store: Typestore, store_name: str, **values: Any) -> Any:
    """An instance of `store_name` with `values` set and every other field at its default."""
    return defaults_plan(store, store_name).new(values)
