"""Per-wheel lateral force, slip angle, cornering stiffness and vertical load.

The axle lateral forces are the ones the motion implies (Newton–Euler on the
body), so they agree with the reported acceleration in every blend regime; in
the purely dynamic regime they equal the linear tyre forces. Each axle's
force and cornering stiffness are split between its wheels in proportion to
their vertical load: static front/rear split from the CG position, lateral
transfer m·ay·h/track shared by the axles in proportion to their static load.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from egosim.world.vehicle.catalogue import GRAVITY, VehicleModel
from egosim.world.vehicle.state import VehicleState


@dataclass(frozen=True, slots=True)
class WheelStatus:
    lateral_force: float
    """Force along the body y axis (left positive), N."""
    slip_angle: float
    """rad; positive when the tyre pushes the car to the left (positive force)."""
    cornering_stiffness: float
    """This wheel's share of its axle's cornering stiffness, N/rad."""
    vertical_load: float
    """N."""


@dataclass(frozen=True, slots=True)
class Wheels:
    front_left: WheelStatus
    front_right: WheelStatus
    rear_left: WheelStatus
    rear_right: WheelStatus


def axle_lateral_forces(model: VehicleModel, state: VehicleState) -> tuple[float, float]:
    """(front, rear) axle lateral forces (N) that produce the state's ay and yaw acceleration."""
    lateral = model.mass * state.ay
    yaw_moment = model.yaw_inertia * state.yaw_acceleration
    wheelbase = model.wheelbase
    front = (lateral * model.cg_to_rear_axle + yaw_moment) / wheelbase
    rear = (lateral * model.cg_to_front_axle - yaw_moment) / wheelbase
    return front, rear


def left_load_share(model: VehicleModel, ay: float) -> float:
    """Fraction (0..1) of each axle's load on its left wheel at lateral acceleration ay (m/s²)."""
    transfer = ay * model.cg_height / (GRAVITY * model.track_width)
    return min(max(0.5 - 0.5 * transfer, 0.0), 1.0)


def slip_angle(steer: float, wheel_vx: float, wheel_vy: float) -> float:
    """Angle (rad) between the wheel's heading and its velocity, signed like the force it causes."""
    cos_steer, sin_steer = math.cos(steer), math.sin(steer)
    along_wheel = wheel_vx * cos_steer + wheel_vy * sin_steer
    across_wheel = -wheel_vx * sin_steer + wheel_vy * cos_steer
    return math.atan2(-across_wheel, abs(along_wheel))


def wheel_statuses(model: VehicleModel, state: VehicleState) -> Wheels:
    """Every wheel's status for the state's last step."""
    front_force, rear_force = axle_lateral_forces(model, state)
    left_share = left_load_share(model, state.ay)
    right_share = 1.0 - left_share
    weight = model.mass * GRAVITY
    front_load = weight * model.cg_to_rear_axle / model.wheelbase
    rear_load = weight - front_load
    half_track = model.track_width / 2.0
    r = state.yaw_rate

    def wheel(
        x: float,
        y: float,
        steer: float,
        axle_force: float,
        stiffness: float,
        load: float,
        share: float,
    ) -> WheelStatus:
        return WheelStatus(
            lateral_force=axle_force * share,
            slip_angle=slip_angle(steer, state.vx - r * y, state.vy + r * x),
            cornering_stiffness=stiffness * share,
            vertical_load=load * share,
        )

    front_x, rear_x = model.cg_to_front_axle, -model.cg_to_rear_axle
    cf, cr = model.cornering_stiffness_front, model.cornering_stiffness_rear
    front_steer, rear_steer = state.front_steer, state.rear_steer
    return Wheels(
        front_left=wheel(front_x, half_track, front_steer, front_force, cf, front_load, left_share),
        front_right=wheel(
            front_x, -half_track, front_steer, front_force, cf, front_load, right_share
        ),
        rear_left=wheel(rear_x, half_track, rear_steer, rear_force, cr, rear_load, left_share),
        rear_right=wheel(rear_x, -half_track, rear_steer, rear_force, cr, rear_load, right_share),
    )
