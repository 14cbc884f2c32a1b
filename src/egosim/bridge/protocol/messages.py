"""Small builders for the nested standard messages every bridge module fills.

A tick makes dozens of these, each with every field given, so they call the message
classes themselves: `MessageType.new` would check the fields and work out defaults
that none of them needs.
"""

from __future__ import annotations

import functools
from collections.abc import Sequence
from typing import Any

from ...msgs import Profile


@functools.cache
def message_class(profile: Profile, name: str) -> Any:
    """The class of the message type `name` of `profile`; call it with every field."""
    message_type = profile.message(name)
    return message_type.store.types[message_type.store_name]


def vector3(profile: Profile, xyz: Sequence[float]) -> Any:
    x, y, z = xyz
    return message_class(profile, "geometry_msgs/Vector3")(x=float(x), y=float(y), z=float(z))


def point(profile: Profile, xyz: Sequence[float]) -> Any:
    x, y, z = xyz
    return message_class(profile, "geometry_msgs/Point")(x=float(x), y=float(y), z=float(z))


def quaternion(profile: Profile, xyzw: Sequence[float]) -> Any:
    x, y, z, w = xyzw
    return message_class(profile, "geometry_msgs/Quaternion")(
        x=float(x), y=float(y), z=float(z), w=float(w)
    )


def time_msg(profile: Profile, total_ns: int) -> Any:
    """A ROS time from nanoseconds (non-negative), split into sec and nanosec."""
    sec, nanosec = divmod(total_ns, 1_000_000_000)
    return message_class(profile, "builtin_interfaces/msg/Time")(sec=sec, nanosec=nanosec)


def header(profile: Profile, stamp_ns: int, frame_id: str, seq: int = 0) -> Any:
    return message_class(profile, "std_msgs/Header")(
        seq=seq, stamp=time_msg(profile, stamp_ns), frame_id=frame_id
    )
