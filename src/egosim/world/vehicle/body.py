"""What every vehicle model has, whatever moves it: a name, a body and a mass."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class VehicleBody:
    """Dimensions (m) and mass (kg) shared by car and ground-vehicle models."""

    name: str
    length: float
    """Overall length, m."""
    width: float
    """Overall width without mirrors, m."""
    height: float
    """Overall height, m."""
    wheelbase: float
    """Front (first) axle to rear (last) axle, m."""
    front_overhang: float
    """Front axle to the front of the body, m."""
    rear_overhang: float
    """Rear axle to the back of the body, m."""
    track_width: float
    """Lateral distance between the left and right wheel (or track) centres, m."""
    mass: float
    """Mass in running order, kg."""
