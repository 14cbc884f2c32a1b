"""Steering actuator: road-wheel angle follows its target at a limited rate."""

from __future__ import annotations


def steer_towards(current: float, target: float, max_rate: float, dt: float) -> float:
    """Road-wheel angle (rad) after dt (s), moving towards target at most max_rate (rad/s)."""
    max_change = max_rate * dt
    return current + min(max(target - current, -max_change), max_change)
