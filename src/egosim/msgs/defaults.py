"""Default-valued messages: zeros, empty strings and empty arrays, as genpy builds them.

Builders make tens of thousands of messages a second, so how to make each type's
defaults is worked out once per type (a `DefaultsPlan`), not per message.
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from dataclasses import dataclass
from typing import cast

import numpy as np
from rosbags.interfaces import Nodetype
from rosbags.interfaces.typing import FieldDesc
from rosbags.typesys.store import Typestore

from .values import BaseValue, FieldValue, Message

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

Maker = Callable[[], FieldValue]
"""Makes a fresh default value of one field."""


def default_base(typename: str) -> BaseValue:
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
    message_class: type[Message]
    field_names: frozenset[str]
    constants: dict[str, BaseValue]
    """Defaults of the base-type fields: immutable, so every message may share them."""
    makers: tuple[tuple[str, Maker], ...]
    """The other fields (messages, lists, arrays): made afresh for each message, so no
    two messages ever share a mutable default."""

    def new(self, **values: FieldValue) -> Message:
        """A message with `values` set and every other field at its default."""
        if not values.keys() <= self.field_names:
            unknown = sorted(set(values) - self.field_names)
            raise TypeError(f"{self.store_name} has no field(s) {', '.join(unknown)}")
        if len(values) == len(self.field_names):  # every field given: no default to make
            return self.message_class(**values)
        fields: dict[str, FieldValue] = {**self.constants, **values}
        for name, make in self.makers:
            if name not in values:
                fields[name] = make()
        return self.message_class(**fields)

    def fresh(self) -> Message:
        """A message with every field at its default."""
        return self.message_class(**self.constants, **{name: make() for name, make in self.makers})


@functools.cache
def defaults_plan(store: Typestore, store_name: str) -> DefaultsPlan:
    """The plan of `store_name`, worked out on first use (a store's types never change once
    registered)."""
    fields = store.fielddefs[store_name][1]
    constants: dict[str, BaseValue] = {}
    makers: list[tuple[str, Maker]] = []
    for name, desc in fields:
        if desc[0] == Nodetype.BASE:
            constants[name] = default_base(desc[1][0])
        else:
            makers.append((name, field_maker(store, desc)))
    return DefaultsPlan(
        store_name=store_name,
        # rosbags generates a dataclass per type (its stubs promise only a constructor)
        message_class=cast("type[Message]", store.types[store_name]),
        field_names=frozenset(name for name, _ in fields),
        constants=constants,
        makers=tuple(makers),
    )


def field_maker(store: Typestore, desc: FieldDesc) -> Maker:
    if desc[0] == Nodetype.BASE:
        return functools.partial(default_base, desc[1][0])
    if desc[0] == Nodetype.NAME:
        return defaults_plan(store, desc[1]).fresh
    element, count = desc[1]
    if element[0] == Nodetype.BASE and element[1][0] != "string":
        dtype = NUMPY_DTYPES[element[1][0]]
        return functools.partial(np.zeros, 0 if desc[0] == Nodetype.SEQUENCE else count, dtype)
    if desc[0] == Nodetype.SEQUENCE:
        return list
    if element[0] == Nodetype.NAME:
        make_message = defaults_plan(store, element[1]).fresh
        return lambda: [make_message() for _ in range(count)]
    return lambda: [""] * count  # a fixed-length array of strings


def default_message(store: Typestore, store_name: str, **values: FieldValue) -> Message:
    """An instance of `store_name` with `values` set and every other field at its default."""
    return defaults_plan(store, store_name).new(**values)
