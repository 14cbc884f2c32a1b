"""Default-valued messages: zeros, empty strings and empty arrays, as genpy builds them."""

from __future__ import annotations

from typing import Any

import numpy as np
from rosbags.typesys.base import Nodetype
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


def default_base(typename: str) -> Any:
    if typename == "string":
        return ""
    if typename == "bool":
        return False
    if typename.startswith("float"):
        return 0.0
    return 0


def default_field(store: Typestore, desc: tuple[Any, Any]) -> Any:
    nodetype, args = desc
    if nodetype == Nodetype.BASE:
        return default_base(args[0])
    if nodetype == Nodetype.NAME:
        return default_message(store, args)
    (subtype, subargs), count = args
    is_numeric = subtype == Nodetype.BASE and subargs[0] != "string"
    if nodetype == Nodetype.SEQUENCE:
        return np.zeros(0, NUMPY_DTYPES[subargs[0]]) if is_numeric else []
    if is_numeric:
        return np.zeros(count, NUMPY_DTYPES[subargs[0]])
    return [default_field(store, (subtype, subargs)) for _ in range(count)]


def default_message(store: Typestore, store_name: str, **values: Any) -> Any:
    """An instance of `store_name` with `values` set and every other field at its default."""
    fields = store.fielddefs[store_name][1]
    unknown = set(values) - {name for name, _ in fields}
    if unknown:
        raise TypeError(f"{store_name} has no field(s) {', '.join(sorted(unknown))}")
    kwargs = {
        name: values[name] if name in values else default_field(store, desc)
        for name, desc in fields
    }
    return store.types[store_name](**kwargs)
