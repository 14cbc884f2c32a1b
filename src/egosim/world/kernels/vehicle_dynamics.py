"""The single-track vehicle's integration step (vehicle/dynamics.py's advance) compiled:
the same float operations in the same order as the Python code, Python's min, max and
math.remainder included."""

from __future__ import annotations

import math

from egosim.world.arrays import FloatArray
from egosim.world.kernels import kernel
from egosim.world.kernels.numpy_scalars import ieee_remainder, python_max, python_min

STATE_FIELDS = (
    "x", "y", "z", "roll", "pitch", "yaw", "vx", "vy", "yaw_rate", "front_steer",
    "rear_steer", "vx_rate", "vy_rate", "yaw_acceleration",
)  # fmt: skip
"""VehicleState's fields in the order of the kernel's state array."""
MODEL_FIELDS = (
    "max_steer_rate", "max_drive_force", "max_power", "max_reverse_speed", "max_speed",
    "drag_area", "mass", "rolling_resistance_coeff", "max_brake_force", "yaw_inertia",
    "cg_to_front_axle", "cg_to_rear_axle", "cornering_stiffness_front",
    "cornering_stiffness_rear", "wheelbase",
)  # fmt: skip
"""VehicleModel's figures in the order of the kernel's model array."""


@kernel
def _steer_towards(current: float, target: float, max_rate: float, dt: float) -> float:
    max_change = max_rate * dt
    return current + python_min(python_max(target - current, -max_change), max_change)


@kernel
def _advance_once(
    model: FloatArray,
    state: FloatArray,
    pedals: FloatArray,
    drive_direction: int,
    parking: bool,
    physics: FloatArray,
    dt: float,
) -> None:
    """One integration step of dt: see advance."""
    (
        max_steer_rate, max_drive_force, max_power, max_reverse_speed, max_speed, drag_area,
        mass, rolling_coeff, max_brake_force, yaw_inertia, a, b, cf, cr, wheelbase,
    ) = model  # fmt: skip
    air_density, gravity, governor_band, blend_start, blend_end = physics
    accel_pedal, brake_pedal, front_target, rear_target = pedals
    state[9] = _steer_towards(state[9], front_target, max_steer_rate, dt)
    state[10] = _steer_towards(state[10], rear_target, max_steer_rate, dt)
    pitch, roll = state[4], state[3]
    vx, vy, yaw_rate = state[6], state[7], state[8]
    front_steer, rear_steer = state[9], state[10]

    # longitudinal.drive_force, grade_force, aero_drag_force, holding_force, next_speed
    capacity = max_drive_force if abs(vx) * max_drive_force <= max_power else max_power / abs(vx)
    force = accel_pedal * capacity
    limit = max_reverse_speed if drive_direction < 0 else max_speed
    headroom = (limit - drive_direction * vx) / governor_band
    drive = drive_direction * force * python_min(python_max(headroom, 0.0), 1.0)
    driving = (
        drive
        + mass * gravity * math.sin(pitch)
        + -0.5 * air_density * drag_area * vx * abs(vx)
        + mass * yaw_rate * vy
    )
    holding = (
        brake_pedal * max_brake_force
        + (max_brake_force if parking else 0.0)
        + rolling_coeff * mass * gravity * math.cos(pitch)
    )
    if vx == 0.0:
        if abs(driving) <= holding:
            new_vx = 0.0
        else:
            new_vx = dt * (driving - math.copysign(holding, driving)) / mass
    else:
        moved = vx + dt * (driving - math.copysign(holding, vx)) / mass
        new_vx = 0.0 if moved * vx <= 0.0 else moved

    # dynamic_weight, kinematic_lateral_motion, dynamic_lateral_motion
    weight = python_min(
        python_max((abs(new_vx) - blend_start) / (blend_end - blend_start), 0.0), 1.0
    )
    tan_front, tan_rear = math.tan(front_steer), math.tan(rear_steer)
    new_yaw_rate = new_vx * (tan_front - tan_rear) / wheelbase
    new_vy = new_vx * (b * tan_front + a * tan_rear) / wheelbase
    if weight > 0.0:
        u = abs(new_vx)
        a11 = -(cf + cr) / (mass * u)
        a12 = (b * cr - a * cf) / (mass * u) - new_vx
        a21 = (b * cr - a * cf) / (yaw_inertia * u)
        a22 = -(a * a * cf + b * b * cr) / (yaw_inertia * u)
        c1 = new_vx * (cf * front_steer + cr * rear_steer) / (mass * u)
        c2 = new_vx * (a * cf * front_steer - b * cr * rear_steer) / (yaw_inertia * u)
        m11 = 1.0 - dt * a11
        m12 = -dt * a12
        m21 = -dt * a21
        m22 = 1.0 - dt * a22
        rhs1 = vy + dt * c1
        rhs2 = yaw_rate + dt * c2
        det = m11 * m22 - m12 * m21
        dynamic_vy = (rhs1 * m22 - m12 * rhs2) / det
        dynamic_yaw_rate = (m11 * rhs2 - m21 * rhs1) / det
        new_vy += weight * (dynamic_vy - new_vy)
        new_yaw_rate += weight * (dynamic_yaw_rate - new_yaw_rate)

    state[11] = (new_vx - vx) / dt
    state[12] = (new_vy - vy) / dt
    state[13] = (new_yaw_rate - yaw_rate) / dt
    state[6], state[7], state[8] = new_vx, new_vy, new_yaw_rate

    cos_roll, sin_roll = math.cos(roll), math.sin(roll)
    cos_pitch, sin_pitch = math.cos(pitch), math.sin(pitch)
    cos_yaw, sin_yaw = math.cos(state[5]), math.sin(state[5])
    level_forward = new_vx * cos_pitch + new_vy * sin_roll * sin_pitch
    level_left = new_vy * cos_roll
    state[0] += dt * (level_forward * cos_yaw - level_left * sin_yaw)
    state[1] += dt * (level_forward * sin_yaw + level_left * cos_yaw)
    state[2] += dt * (-new_vx * sin_pitch + new_vy * sin_roll * cos_pitch)
    state[5] += dt * new_yaw_rate * cos_roll / cos_pitch
    state[5] = ieee_remainder(state[5], math.tau)


@kernel
def advance(
    model: FloatArray,
    state: FloatArray,
    pedals: FloatArray,
    drive_direction: int,
    parking: bool,
    physics: FloatArray,
    dt: float,
    repeats: int,
) -> None:
    """dynamics.advance on `state` (STATE_FIELDS) in place, `repeats` times over dt with
    the same inputs. pedals: accel, brake, front and rear steer targets; physics: air
    density, gravity, governor band, blend start and end speeds."""
    for _ in range(repeats):
        _advance_once(model, state, pedals, drive_direction, parking, physics, dt)
