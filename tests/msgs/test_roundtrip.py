"""Populated instances of every type survive serialisation unchanged."""

from __future__ import annotations

import random
from typing import Any

import numpy as np
import pytest
from rosbags.typesys.base import Nodetype

from egosim.msgs import MessageType, SerializationError, get_profile
from egosim.msgs.defaults import NUMPY_DTYPES

PROFILE = "26.r1"

INT_RANGES = {
    "byte": (-128, 127),
    "char": (0, 255),
    "int8": (-128, 127),
    "uint8": (0, 255),
    "int16": (-(2**15), 2**15 - 1),
    "uint16": (0, 2**16 - 1),
    "int32": (-(2**31), 2**31 - 1),
    "uint32": (0, 2**32 - 1),
    "int64": (-(2**63), 2**63 - 1),
    "uint64": (0, 2**64 - 1),
}


def populated_base(typename: str, rng: random.Random) -> Any:
    if typename == "string":
        return "".join(rng.choice("abcXYZ_/ 0129") for _ in range(rng.randint(1, 12)))
    if typename == "bool":
        return rng.random() < 0.5
    if typename == "float32":
        return float(np.float32(rng.uniform(-1e3, 1e3)))
    if typename == "float64":
        return rng.uniform(-1e6, 1e6)
    low, high = INT_RANGES[typename]
    return rng.randint(low, high)


def populated(message_type: MessageType, store_name: str, rng: random.Random) -> Any:
    store = message_type.store
    values = {}
    for name, (nodetype, args) in store.fielddefs[store_name][1]:
        if nodetype == Nodetype.BASE:
            values[name] = populated_base(args[0], rng)
        elif nodetype == Nodetype.NAME:
            values[name] = populated(message_type, args, rng)
        else:
            (subtype, subargs), count = args
            length = count if nodetype == Nodetype.ARRAY else rng.randint(1, 3)
            if subtype == Nodetype.BASE and subargs[0] != "string":
                items = [populated_base(subargs[0], rng) for _ in range(length)]
                values[name] = np.array(items, dtype=NUMPY_DTYPES[subargs[0]])
            elif subtype == Nodetype.BASE:
                values[name] = [populated_base("string", rng) for _ in range(length)]
            else:
                values[name] = [populated(message_type, subargs, rng) for _ in range(length)]
    return store.types[store_name](**values)


def every_message_type() -> list[str]:
    profile = get_profile(PROFILE)
    names = list(profile.message_names())
    for service in profile.service_names():
        names += [f"{service}Request", f"{service}Response"]
    return names


@pytest.mark.parametrize("name", every_message_type())
def test_populated_message_round_trips(name: str) -> None:
    message_type = get_profile(PROFILE).message(name)
    original = populated(message_type, message_type.store_name, random.Random(name))
    data = message_type.serialize(original)
    decoded = message_type.deserialize(data)
    assert message_type.serialize(decoded) == data
    assert repr(decoded) == repr(original)


@pytest.mark.parametrize("name", every_message_type())
def test_default_message_serializes(name: str) -> None:
    message_type = get_profile(PROFILE).message(name)
    data = message_type.serialize(message_type.new())
    assert message_type.serialize(message_type.deserialize(data)) == data


def mutable_parts(value: Any) -> list[Any]:
    """`value` and every message, list and array inside it (strings and numbers excluded)."""
    if isinstance(value, str | int | float | bool):
        return []
    if isinstance(value, np.ndarray):
        return [value]
    inner = value if isinstance(value, list) else vars(value).values()
    return [value, *(part for item in inner for part in mutable_parts(item))]


@pytest.mark.parametrize("name", every_message_type())
def test_default_messages_share_no_mutable_value(name: str) -> None:
    message_type = get_profile(PROFILE).message(name)
    first, second = message_type.new(), message_type.new()
    first_ids = {id(part) for part in mutable_parts(first)}
    assert not first_ids & {id(part) for part in mutable_parts(second)}


def test_new_rejects_unknown_fields() -> None:
    with pytest.raises(TypeError, match="steering"):
        get_profile(PROFILE).message("morai_msgs/CtrlCmd").new(steering=0.1)


def test_truncated_bytes_raise_serialization_error() -> None:
    status = get_profile(PROFILE).message("morai_msgs/EgoVehicleStatus")
    data = status.serialize(status.new())
    with pytest.raises(SerializationError, match="EgoVehicleStatus"):
        status.deserialize(data[:-5])
