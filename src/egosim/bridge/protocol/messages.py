"""Small builders for the nested standard messages every bridge module fills."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from ...msgs import Profile


def vector3(profile: Profile, xyz: Sequence[float]) -> Any:
    x, y, z = xyz
    return profile.message("geometry_msgs/Vector3").new(x=float(x), y=float(y), z=float(z))


def quaternion(profile: Profile, xyzw: Sequence[float]) -> Any:
    x, y, z, w = xyzw
    return profile.message("geometry_msgs/Quaternion").new(
        x=float(x), y=float(y), z=float(z), w=float(w)
    )


def time_msg(profile: Profile, total_ns: int) -> Any:
    """A ROS time from nanoseconds (non-negative), split into sec and nanosec."""
    sec, nanosec = divmod(total_ns, 1_000_000_000)
    return profile.message("builtin_interfaces/msg/Time").new(sec=sec, nanosec=nanosec)


def header(profile: Profile, stamp_ns: int, frame_id: str, seq: int = 0) -> Any:
    return profile.message("std_msgs/Header").new(
        seq=seq, stamp=time_msg(profile, stamp_ns), frame_id=frame_id
    )
