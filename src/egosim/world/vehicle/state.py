"""The vehicle's dynamic state, integrated by dynamics.advance."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(slots=True)
class VehicleState:
    """Pose in the map (ENU) and motion in the body frame (x forward, y left, z up), SI units.

    (x, y, z) is the centre of gravity; roll, pitch, yaw are REP 103 angles (rad).
    The rates are the derivatives over the last integration step.
    """

    x: float = 0.0
    y: float = 0.0
    z: float = 0.0
    roll: float = 0.0
    pitch: float = 0.0
    yaw: float = 0.0
    vx: float = 0.0
    """Longitudinal velocity, m/s."""
    vy: float = 0.0
    """Lateral velocity, m/s."""
    yaw_rate: float = 0.0
    """rad/s, counter-clockwise positive."""
    front_steer: float = 0.0
    """Front road-wheel angle, rad, positive to the left."""
    rear_steer: float = 0.0
    """Rear road-wheel angle, rad, positive to the left."""
    vx_rate: float = 0.0
    """dvx/dt, m/s²."""
    vy_rate: float = 0.0
    """dvy/dt, m/s²."""
    yaw_acceleration: float = 0.0
    """d(yaw_rate)/dt, rad/s²."""

    @property
    def ax(self) -> float:
        """Longitudinal acceleration of the CG in the body frame, m/s²."""
        return self.vx_rate - self.yaw_rate * self.vy

    @property
    def ay(self) -> float:
        """Lateral acceleration of the CG in the body frame, m/s²."""
        return self.vy_rate + self.yaw_rate * self.vx
