"""MORAI scenario units and axes -> egosim's (SI, ENU).

Positions (`pos`) are ENU metres in the map's local frame (east, north, up), headings
(`rot.yaw`) degrees counter-clockwise from east, as /Ego_topic reports them. Waypoint
paths and a few copies (`initPos`, `standardPos`, a saved `lastVelocity`) keep Unity's
axes instead: left-handed, y up, x = -east, z = -north. Speeds are km/h.
"""

from __future__ import annotations

import math

KMH_PER_MPS = 3.6


def unity_to_enu(x: float, y: float, z: float) -> tuple[float, float, float]:
    """A point in Unity's axes -> (east, north, up) m."""
    return -x, -z, y


def heading_of(yaw_deg: float) -> float:
    """A MORAI yaw (deg, counter-clockwise from east) -> egosim's heading (rad, in
    (-pi, pi])."""
    return math.remainder(math.radians(yaw_deg), math.tau)


def mps(kmh: float) -> float:
    return kmh / KMH_PER_MPS
