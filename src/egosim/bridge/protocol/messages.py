"""Small builders for the nested standard messages every bridge module fills.

A tick makes dozens of these, each with every field given, so they build with
`MessageType.make` (the class itself): `MessageType.new` would check the fields and
work out defaults that none of them needs.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ...msgs.typed import standard
    from .releases import CanonicalProfile


def vector3(profile: CanonicalProfile, xyz: Sequence[float]) -> standard.Vector3:
    x, y, z = xyz
    return profile.message("geometry_msgs/Vector3").make(x=float(x), y=float(y), z=float(z))


def point(profile: CanonicalProfile, xyz: Sequence[float]) -> standard.Point:
    x, y, z = xyz
    return profile.message("geometry_msgs/Point").make(x=float(x), y=float(y), z=float(z))


def quaternion(profile: CanonicalProfile, xyzw: Sequence[float]) -> standard.Quaternion:
    x, y, z, w = xyzw
    return profile.message("geometry_msgs/Quaternion").make(
        x=float(x), y=float(y), z=float(z), w=float(w)
    )


def time_msg(profile: CanonicalProfile, total_ns: int) -> standard.Time:
    """A ROS time from nanoseconds (non-negative), split into sec and nanosec."""
    sec, nanosec = divmod(total_ns, 1_000_000_000)
    return profile.message("builtin_interfaces/Time").make(sec=sec, nanosec=nanosec)


def header(
    profile: CanonicalProfile, stamp_ns: int, frame_id: str, seq: int = 0
) -> standard.Header:
    return profile.message("std_msgs/Header").make(
        seq=seq, stamp=time_msg(profile, stamp_ns), frame_id=frame_id
    )
