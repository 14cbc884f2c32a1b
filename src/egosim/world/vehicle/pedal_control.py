"""Controllers that turn a target acceleration or speed into pedal positions.

Acceleration tracking inverts the longitudinal model (feed-forward of the
force the target needs against drag, rolling resistance, grade) and corrects
what the model misses with an integral on the acceleration error. Speed
tracking is a proportional speed loop commanding that acceleration tracker.
Together they are a PI on speed whose integral sits in the inner loop: the
speed loop gets zero steady-state error without the set-point zero that makes
a plain PI overshoot a speed step. The integral is frozen while the pedal it
would push further is saturated and while the car is not moving (anti-windup).
"""

from __future__ import annotations

from dataclasses import dataclass

from egosim.world.vehicle.catalogue import VehicleModel
from egosim.world.vehicle.gear import Gear
from egosim.world.vehicle.longitudinal import (
    aero_drag_force,
    grade_force,
    max_drive_force,
    rolling_resistance_force,
)
from egosim.world.vehicle.state import VehicleState

ACCELERATION_INTEGRAL_GAIN = 2.0
"""Integral gain on the acceleration error, 1/s."""
SPEED_GAIN = 1.0
"""Acceleration demanded per m/s of speed error, 1/s."""
MOVING_SPEED = 0.1
"""Speed (m/s) above which the car counts as moving for the integral."""
STOPPING_DECELERATION = 0.5
"""Least deceleration (m/s²) the speed loop asks for when the target is standstill."""


@dataclass(frozen=True, slots=True)
class Pedals:
    accel: float
    """0..1."""
    brake: float
    """0..1."""


def travel_direction(gear: Gear) -> int:
    """+1 or -1: the direction speeds and accelerations are measured in for this gear."""
    return gear.drive_direction or 1


class AccelerationTracker:
    """Pedals that make the speed along the gear's direction change at a target rate."""

    def __init__(self, model: VehicleModel) -> None:
        self.model = model
        self._correction = 0.0

    def reset(self) -> None:
        self._correction = 0.0

    def pedals(self, target: float, gear: Gear, state: VehicleState, dt: float) -> Pedals:
        """Pedals for target (m/s²) this step; state holds the last step's acceleration."""
        model = self.model
        direction = travel_direction(gear)
        speed = direction * state.vx
        demand = target + self._correction
        external = (
            grade_force(model, state.pitch)
            + aero_drag_force(model, state.vx)
            + model.mass * state.yaw_rate * state.vy
        )
        force = model.mass * demand - direction * external
        if speed > 0.0 or demand > 0.0:
            force += rolling_resistance_force(model, state.pitch)
        if force > 0.0:
            capacity = max_drive_force(model, state.vx) if gear.drive_direction else 0.0
            accel = min(force / capacity, 1.0) if capacity else 0.0
            pedals = Pedals(accel=accel, brake=0.0)
        else:
            pedals = Pedals(accel=0.0, brake=min(-force / model.max_brake_force, 1.0))

        error = target - direction * state.vx_rate
        pushes_saturated = (error > 0.0 and (pedals.accel >= 1.0 or not gear.drive_direction)) or (
            error < 0.0 and pedals.brake >= 1.0
        )
        if speed > MOVING_SPEED and not pushes_saturated:
            self._correction += ACCELERATION_INTEGRAL_GAIN * error * dt
        return pedals


class SpeedController:
    """Pedals that bring the speed along the gear's direction to a target."""

    def __init__(self, model: VehicleModel, tracker: AccelerationTracker) -> None:
        self.model = model
        self.tracker = tracker

    def pedals(self, target: float, gear: Gear, state: VehicleState, dt: float) -> Pedals:
        """Pedals for a target speed (m/s, >= 0) this step."""
        model = self.model
        target = min(target, model.max_reverse_speed if gear is Gear.REVERSE else model.max_speed)
        speed = travel_direction(gear) * state.vx
        acceleration = SPEED_GAIN * (target - speed)
        if target == 0.0:
            # An exponential approach never reaches rest: a stop ends at a firm,
            # constant deceleration, and the brakes then hold the car.
            acceleration = min(acceleration, -STOPPING_DECELERATION)
        acceleration = min(
            max(acceleration, -model.max_brake_decel), model.max_drive_force / model.mass
        )
        return self.tracker.pedals(acceleration, gear, state, dt)
