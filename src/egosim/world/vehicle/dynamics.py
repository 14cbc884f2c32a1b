"""Single-track (bicycle) model with linear tyres, blended to the kinematic model at low speed.

Lateral dynamics (small angles, a = CG to front axle, b = CG to rear axle,
u = |vx|, so the same equations hold when reversing):

    F_yf = C_f·(vx·δ_f − vy − a·r)/u        F_yr = C_r·(vx·δ_r − vy + b·r)/u
    m·(dvy/dt + vx·r) = F_yf + F_yr         I_z·dr/dt = a·F_yf − b·F_yr

They are linear in (vy, r) for a given vx and are integrated with implicit
Euler: unconditionally stable however small u gets, and its fixed point is the
exact steady state of the continuous model. The 1/u stiffness still makes the
tyre model meaningless near standstill, so between BLEND_START and BLEND_END
the result is blended linearly with the kinematic bicycle, whose velocities
follow from geometry alone:

    r = vx·(tan δ_f − tan δ_r)/L            vy = vx·(b·tan δ_f + a·tan δ_r)/L
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from egosim.world import kernels
from egosim.world.arrays import FloatArray
from egosim.world.kernels import vehicle_dynamics
from egosim.world.vehicle.catalogue import GRAVITY, VehicleModel
from egosim.world.vehicle.gear import Gear
from egosim.world.vehicle.longitudinal import (
    AIR_DENSITY,
    GOVERNOR_BAND,
    aero_drag_force,
    drive_force,
    grade_force,
    holding_force,
    next_speed,
)
from egosim.world.vehicle.state import VehicleState
from egosim.world.vehicle.steering import steer_towards

BLEND_START = 1.0
"""Speed (m/s) below which the motion is purely kinematic."""
BLEND_END = 3.0
"""Speed (m/s) above which the motion is purely dynamic."""


@dataclass(frozen=True, slots=True)
class ActuatorInputs:
    """What the driver (or controller) applies during a step."""

    accel_pedal: float
    """0..1."""
    brake_pedal: float
    """0..1."""
    front_steer_target: float
    """rad, within the model's limits."""
    rear_steer_target: float
    """rad, within the model's limits."""
    gear: Gear


def dynamic_weight(speed: float) -> float:
    """Share (0..1) of the dynamic model in the blend at this speed (m/s)."""
    return min(max((abs(speed) - BLEND_START) / (BLEND_END - BLEND_START), 0.0), 1.0)


def kinematic_lateral_motion(
    model: VehicleModel, vx: float, front_steer: float, rear_steer: float
) -> tuple[float, float]:
    """(vy, yaw rate) of the kinematic bicycle: both axles roll without side slip."""
    tan_front = math.tan(front_steer)
    tan_rear = math.tan(rear_steer)
    wheelbase = model.wheelbase
    yaw_rate = vx * (tan_front - tan_rear) / wheelbase
    vy = vx * (model.cg_to_rear_axle * tan_front + model.cg_to_front_axle * tan_rear) / wheelbase
    return vy, yaw_rate


def dynamic_lateral_motion(
    model: VehicleModel,
    vy: float,
    yaw_rate: float,
    vx: float,
    front_steer: float,
    rear_steer: float,
    dt: float,
) -> tuple[float, float]:
    """(vy, yaw rate) after one implicit Euler step of the linear single-track model."""
    m = model.mass
    inertia = model.yaw_inertia
    a = model.cg_to_front_axle
    b = model.cg_to_rear_axle
    cf = model.cornering_stiffness_front
    cr = model.cornering_stiffness_rear
    u = abs(vx)
    # d/dt [vy, r] = A·[vy, r] + c
    a11 = -(cf + cr) / (m * u)
    a12 = (b * cr - a * cf) / (m * u) - vx
    a21 = (b * cr - a * cf) / (inertia * u)
    a22 = -(a * a * cf + b * b * cr) / (inertia * u)
    c1 = vx * (cf * front_steer + cr * rear_steer) / (m * u)
    c2 = vx * (a * cf * front_steer - b * cr * rear_steer) / (inertia * u)
    # (I − dt·A)·x_next = x + dt·c, solved by Cramer's rule.
    m11 = 1.0 - dt * a11
    m12 = -dt * a12
    m21 = -dt * a21
    m22 = 1.0 - dt * a22
    rhs1 = vy + dt * c1
    rhs2 = yaw_rate + dt * c2
    det = m11 * m22 - m12 * m21
    return (rhs1 * m22 - m12 * rhs2) / det, (m11 * rhs2 - m21 * rhs1) / det


_PHYSICS = np.array((AIR_DENSITY, GRAVITY, GOVERNOR_BAND, BLEND_START, BLEND_END))
_FIGURES: dict[int, tuple[VehicleModel, FloatArray]] = {}


def _figures(model: VehicleModel) -> FloatArray:
    """The model's figures as kernels/vehicle_dynamics.py takes them, kept per model."""
    known = _FIGURES.get(id(model))
    if known is None or known[0] is not model:
        if len(_FIGURES) > 64:
            _FIGURES.clear()
        figures = np.array([getattr(model, name) for name in vehicle_dynamics.MODEL_FIELDS])
        known = _FIGURES[id(model)] = (model, figures)
    return known[1]


def advance(
    model: VehicleModel, state: VehicleState, inputs: ActuatorInputs, dt: float, repeats: int = 1
) -> None:
    """Integrate the state in place over `repeats` steps of dt (s) with the same inputs:
    in each, the actuators, then the speeds, then the pose."""
    if kernels.ACTIVE:
        _advance_compiled(model, state, inputs, dt, repeats)
        return
    for _ in range(repeats):
        _advance_once(model, state, inputs, dt)


def _advance_once(
    model: VehicleModel, state: VehicleState, inputs: ActuatorInputs, dt: float
) -> None:
    state.front_steer = steer_towards(
        state.front_steer, inputs.front_steer_target, model.max_steer_rate, dt
    )
    state.rear_steer = steer_towards(
        state.rear_steer, inputs.rear_steer_target, model.max_steer_rate, dt
    )

    vx, vy, yaw_rate = state.vx, state.vy, state.yaw_rate
    driving = (
        drive_force(model, inputs.gear, inputs.accel_pedal, vx)
        + grade_force(model, state.pitch)
        + aero_drag_force(model, vx)
        + model.mass * yaw_rate * vy
    )
    holding = holding_force(model, inputs.gear, inputs.brake_pedal, state.pitch)
    new_vx = next_speed(vx, driving, holding, model.mass, dt)

    weight = dynamic_weight(new_vx)
    new_vy, new_yaw_rate = kinematic_lateral_motion(
        model, new_vx, state.front_steer, state.rear_steer
    )
    if weight > 0.0:
        dynamic_vy, dynamic_yaw_rate = dynamic_lateral_motion(
            model, vy, yaw_rate, new_vx, state.front_steer, state.rear_steer, dt
        )
        new_vy += weight * (dynamic_vy - new_vy)
        new_yaw_rate += weight * (dynamic_yaw_rate - new_yaw_rate)

    state.vx_rate = (new_vx - vx) / dt
    state.vy_rate = (new_vy - vy) / dt
    state.yaw_acceleration = (new_yaw_rate - yaw_rate) / dt
    state.vx, state.vy, state.yaw_rate = new_vx, new_vy, new_yaw_rate

    # Body velocity (vx, vy, 0) rotated into the map by Rz(yaw)·Ry(pitch)·Rx(roll).
    cos_roll, sin_roll = math.cos(state.roll), math.sin(state.roll)
    cos_pitch, sin_pitch = math.cos(state.pitch), math.sin(state.pitch)
    cos_yaw, sin_yaw = math.cos(state.yaw), math.sin(state.yaw)
    level_forward = new_vx * cos_pitch + new_vy * sin_roll * sin_pitch
    level_left = new_vy * cos_roll
    state.x += dt * (level_forward * cos_yaw - level_left * sin_yaw)
    state.y += dt * (level_forward * sin_yaw + level_left * cos_yaw)
    state.z += dt * (-new_vx * sin_pitch + new_vy * sin_roll * cos_pitch)
    # Euler-angle rate of a body turning about its own z axis on a tilted road.
    state.yaw += dt * new_yaw_rate * cos_roll / cos_pitch
    state.yaw = math.remainder(state.yaw, math.tau)


def _advance_compiled(
    model: VehicleModel, state: VehicleState, inputs: ActuatorInputs, dt: float, repeats: int
) -> None:
    """advance() through kernels/vehicle_dynamics.py: the same arithmetic, the same results."""
    values = np.array(
        (
            state.x, state.y, state.z, state.roll, state.pitch, state.yaw, state.vx,
            state.vy, state.yaw_rate, state.front_steer, state.rear_steer, state.vx_rate,
            state.vy_rate, state.yaw_acceleration,
        )
    )  # fmt: skip
    vehicle_dynamics.advance(
        _figures(model),
        values,
        np.array(
            (
                inputs.accel_pedal,
                inputs.brake_pedal,
                inputs.front_steer_target,
                inputs.rear_steer_target,
            )
        ),
        inputs.gear.drive_direction,
        inputs.gear is Gear.PARKING,
        _PHYSICS,
        dt,
        repeats,
    )
    (
        state.x, state.y, state.z, state.roll, state.pitch, state.yaw, state.vx, state.vy,
        state.yaw_rate, state.front_steer, state.rear_steer, state.vx_rate, state.vy_rate,
        state.yaw_acceleration,
    ) = values.tolist()  # fmt: skip
