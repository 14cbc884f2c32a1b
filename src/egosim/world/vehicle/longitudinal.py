"""Longitudinal forces along body x: powertrain, brakes, rolling resistance, drag, grade.

Forces are split in two kinds. Driving forces (powertrain, gravity along the
grade, aerodynamic drag) act whatever the motion. Holding forces (brakes,
parking lock, rolling resistance) are Coulomb-like: they oppose the motion and,
at standstill, hold the car against up to their full magnitude but never push
it, so braking stops the car and never drives it backwards.
"""

from __future__ import annotations

import math

from egosim.world.vehicle.catalogue import GRAVITY, VehicleModel
from egosim.world.vehicle.gear import Gear

AIR_DENSITY = 1.225
"""Sea-level ISA air density, kg/m³."""

GOVERNOR_BAND = 1.0
"""Speed band below max_speed (forwards) or max_reverse_speed over which the drive
fades out, m/s."""


def max_drive_force(model: VehicleModel, speed: float) -> float:
    """Largest tractive force at speed (m/s), N: torque-limited, then power-limited (F ≤ P/v)."""
    magnitude = abs(speed)
    if magnitude * model.max_drive_force <= model.max_power:
        return model.max_drive_force
    return model.max_power / magnitude


def drive_force(model: VehicleModel, gear: Gear, accel_pedal: float, vx: float) -> float:
    """Powertrain force along body x (N) for a pedal in 0..1 at body speed vx (m/s)."""
    direction = gear.drive_direction
    force = accel_pedal * max_drive_force(model, vx)
    limit = model.max_reverse_speed if direction < 0 else model.max_speed
    headroom = (limit - direction * vx) / GOVERNOR_BAND
    return direction * force * min(max(headroom, 0.0), 1.0)


def aero_drag_force(model: VehicleModel, vx: float) -> float:
    """½·ρ·Cd·A·v² opposing the motion, N along body x."""
    return -0.5 * AIR_DENSITY * model.drag_area * vx * abs(vx)


def grade_force(model: VehicleModel, pitch: float) -> float:
    """Gravity along body x, N; REP 103 pitch is positive nose down, so downhill pushes forward."""
    return model.mass * GRAVITY * math.sin(pitch)


def rolling_resistance_force(model: VehicleModel, pitch: float) -> float:
    """Magnitude of the rolling resistance on a road pitched by `pitch` (rad), N."""
    return model.rolling_resistance_coeff * model.mass * GRAVITY * math.cos(pitch)


def holding_force(model: VehicleModel, gear: Gear, brake_pedal: float, pitch: float) -> float:
    """Magnitude of the Coulomb-like forces (brake, parking lock, rolling resistance), N."""
    # The parking pawl locks the driven wheels; it is modelled as holding as
    # hard as the service brake, far more than any road grade needs.
    parking = model.max_brake_force if gear is Gear.PARKING else 0.0
    return brake_pedal * model.max_brake_force + parking + rolling_resistance_force(model, pitch)


def next_speed(vx: float, driving: float, holding: float, mass: float, dt: float) -> float:
    """Body speed after dt (s) under driving force and holding-force magnitude (N).

    A car that stops within the step (its speed would change sign) ends it at
    rest; at rest it moves off only once the driving force exceeds the holding.
    """
    if vx == 0.0:
        if abs(driving) <= holding:
            return 0.0
        return dt * (driving - math.copysign(holding, driving)) / mass
    moved = vx + dt * (driving - math.copysign(holding, vx)) / mass
    if moved * vx <= 0.0:
        return 0.0
    return moved
