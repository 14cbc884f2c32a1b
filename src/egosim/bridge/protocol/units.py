"""Protocol units at the edge: the world is SI (m, s, rad, m/s); MORAI speaks deg and km/h."""

from __future__ import annotations

import math
from collections.abc import Sequence

KMH_PER_MPS = 3.6


def deg(radians: float) -> float:
    return math.degrees(radians)


def rad(degrees: float) -> float:
    return math.radians(degrees)


def kmh(mps: float) -> float:
    return mps * KMH_PER_MPS


def mps(kmh_value: float) -> float:
    return kmh_value / KMH_PER_MPS


def heading_deg(yaw: float) -> float:
    """An ENU yaw (rad, 0 = east, CCW) as a heading in deg wrapped to (-180, 180]."""
    degrees = math.degrees(math.atan2(math.sin(yaw), math.cos(yaw)))
    return 180.0 if degrees == -180.0 else degrees


def swap_length_width(size: Sequence[float]) -> tuple[float, float, float]:
    """ObjectStatus.size lists (width, length, height), the world (length, width, height):
    the one swap turns either into the other."""
    first, second, height = size
    return (second, first, height)
