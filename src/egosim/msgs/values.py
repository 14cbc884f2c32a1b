"""What a message is and what its fields hold, for code that sets or reads fields by name.

Messages are the dataclasses rosbags generates for each type. A field holds a base
value, a nested message, a list of messages or strings, or (a numeric array or
sequence) a one-dimensional numpy array, as rosbags deserialises it and as the packer
and the defaults make it. The typed classes of egosim.msgs.typed name each field's own
type; `FieldValue` is what any field of any type may hold.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import Field
from typing import ClassVar, Protocol, TypeAlias

import numpy as np
from numpy.typing import NDArray


class Message(Protocol):
    """A message of any type: an instance of the dataclass rosbags generated for it."""

    __msgtype__: ClassVar[str]  # rosbags' name of its type, `pkg/msg/Name`
    __dataclass_fields__: ClassVar[dict[str, Field[object]]]

    def __init__(self, **fields: FieldValue) -> None: ...


BaseValue: TypeAlias = bool | int | float | str
"""A field of a ROS base type (`time` and `duration` are messages in rosbags)."""

FieldValue: TypeAlias = (
    BaseValue | Message | Sequence[Message] | Sequence[str] | NDArray[np.generic]
)
"""What a field of a message holds."""
