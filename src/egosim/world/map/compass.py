"""Compass labels for directions in ids (N, E, S, W)."""

from __future__ import annotations


def compass(dx: float, dy: float) -> str:
    """The nearest of N/E/S/W to a direction in the ENU plane (ties go east/west)."""
    if abs(dx) >= abs(dy):
        return "E" if dx > 0 else "W"
    return "N" if dy > 0 else "S"
