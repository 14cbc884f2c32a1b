"""The ego vehicle: command gate, pedal controllers and dynamics behind one object."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, NamedTuple

from egosim.world.vehicle.catalogue import DEFAULT_EGO_MODEL, VehicleModel, vehicle_model
from egosim.world.vehicle.control import (
    DEFAULT_COMMAND_TIMEOUT,
    CommandGate,
    ControlCommand,
    LongitudinalMode,
)
from egosim.world.vehicle.dynamics import ActuatorInputs, advance, kinematic_lateral_motion
from egosim.world.vehicle.gear import Gear
from egosim.world.vehicle.pedal_control import AccelerationTracker, Pedals, SpeedController
from egosim.world.vehicle.state import VehicleState
from egosim.world.vehicle.stepping import GatedVehicle, VehicleOptions
from egosim.world.vehicle.wheels import Wheels, wheel_statuses

if TYPE_CHECKING:
    from typing_extensions import Unpack  # typing's own from Python 3.11

DEFAULT_MAX_SUBSTEP = 0.005
"""Longest integration step (s); a step(dt) is split into equal substeps no longer than this."""

Vector3 = tuple[float, float, float]


@dataclass(frozen=True)
class Pose:
    """A frame's position (m) and REP 103 roll, pitch, yaw (rad) in its parent frame.

    A vehicle's pose is its reference point, its base_link, in the map (ENU, yaw 0 = east):
    for a road vehicle MORAI's vehicle origin, the midpoint of the rear axle on the road.
    """

    x: float = 0.0
    y: float = 0.0
    z: float = 0.0
    roll: float = 0.0
    pitch: float = 0.0
    yaw: float = 0.0


@dataclass(frozen=True)
class RoadSurface:
    """The road under the vehicle: height (m) and the REP 103 roll and pitch (rad) it imposes.

    Pitch is positive nose down: facing up a 10 % grade is pitch = -atan(0.1).
    """

    z: float
    pitch: float = 0.0
    roll: float = 0.0


@dataclass(frozen=True)
class VehicleStatus:
    """Everything EgoVehicleStatus needs from the vehicle, SI units.

    Vectors in the body frame are (x forward, y left, z up).
    """

    pose: Pose
    velocity: Vector3
    """Body-frame velocity of the reference point, m/s."""
    acceleration: Vector3
    """Body-frame kinematic acceleration of the reference point (no gravity), m/s²."""
    yaw_rate: float
    """rad/s, counter-clockwise positive."""
    speed: float
    """Magnitude of the velocity, m/s (never negative)."""
    accel_pedal: float
    """Accelerator pedal actually applied, 0..1."""
    brake_pedal: float
    """Brake pedal actually applied, 0..1."""
    front_steer: float
    """Front road-wheel angle, rad, positive to the left."""
    rear_steer: float
    """Rear road-wheel angle, rad, positive to the left."""
    gear: Gear
    wheels: Wheels


class Motion(NamedTuple):
    """Where a vehicle is and how it moves (VehicleStatus's pose, velocity and
    acceleration), without the rest of its status: what the world asks of an ego at
    every step."""

    pose: Pose
    velocity: Vector3
    """Body-frame velocity of the reference point, m/s."""
    acceleration: Vector3
    """Body-frame kinematic acceleration of the reference point (no gravity), m/s²."""


class Vehicle(GatedVehicle[ControlCommand]):
    """One vehicle of a catalogue model; advanced by step(dt) on the road it is given."""

    def __init__(
        self,
        model: VehicleModel,
        pose: Pose | None = None,
        *,
        gear: Gear = Gear.DRIVE,
        command_timeout: float | None = DEFAULT_COMMAND_TIMEOUT,
        max_substep: float = DEFAULT_MAX_SUBSTEP,
    ) -> None:
        self._commands = CommandGate(model, command_timeout)
        super().__init__(self._commands, gear, max_substep)
        self.model = model
        self._state = VehicleState()
        self._acceleration_tracker = AccelerationTracker(model)
        self._speed_controller = SpeedController(model, self._acceleration_tracker)
        self._pedals = Pedals(accel=0.0, brake=0.0)
        # Readers ask for the status many times per step; it changes only when the
        # vehicle is stepped, teleported or shifted.
        self._status: VehicleStatus | None = None
        self._motion: Motion | None = None
        self.teleport(pose or Pose())

    @classmethod
    def from_catalogue(
        cls,
        name: str = DEFAULT_EGO_MODEL,
        pose: Pose | None = None,
        **options: Unpack[VehicleOptions],
    ) -> Vehicle:
        """A vehicle of the catalogue model `name`; options as for the constructor."""
        return cls(vehicle_model(name), pose, **options)

    def hold_speed(self, speed: float) -> None:
        """Keep `speed` (m/s, negative: in reverse) until the first command (a scenario's
        initial speed for a stack that has not spoken yet); the dead-man timeout starts
        with that command."""
        if speed < 0.0:
            self.set_gear(Gear.REVERSE)
        self._commands.hold(ControlCommand(mode=LongitudinalMode.VELOCITY, velocity=abs(speed)))

    def set_gear(self, gear: Gear) -> None:
        self.gear = gear
        self._status = self._motion = None

    def teleport(
        self, pose: Pose, speed: float = 0.0, front_steer: float = 0.0, rear_steer: float = 0.0
    ) -> None:
        """Put the vehicle's reference point (the rear axle's midpoint) at pose, moving at
        speed (m/s, body x) with these wheel angles (rad).

        The lateral motion is the kinematic one for that speed and steering.
        """
        state = self._state
        b = self.model.cg_to_rear_axle
        state.x = pose.x + b * math.cos(pose.yaw)
        state.y = pose.y + b * math.sin(pose.yaw)
        state.z = pose.z
        state.roll, state.pitch, state.yaw = pose.roll, pose.pitch, pose.yaw
        state.vx = speed
        state.front_steer, state.rear_steer = front_steer, rear_steer
        state.vy, state.yaw_rate = kinematic_lateral_motion(
            self.model, speed, front_steer, rear_steer
        )
        state.vx_rate = state.vy_rate = state.yaw_acceleration = 0.0
        self._acceleration_tracker.reset()
        self._status = self._motion = None

    def shove(self, displacement: tuple[float, float], change: tuple[float, float]) -> None:
        """A contact's response: move by `displacement` (m) and change the velocity by
        `change` (m/s), both in the map frame; the yaw rate is kept (contacts act
        through the centre)."""
        state = self._state
        state.x += displacement[0]
        state.y += displacement[1]
        cos_yaw, sin_yaw = math.cos(state.yaw), math.sin(state.yaw)
        state.vx += cos_yaw * change[0] + sin_yaw * change[1]
        state.vy += -sin_yaw * change[0] + cos_yaw * change[1]
        self._status = self._motion = None

    def step(self, dt: float, surface: RoadSurface | None = None) -> None:
        """Advance dt seconds; surface, when given, is the road under the vehicle now."""
        substeps = list(self._substeps(dt))
        state = self._state
        self._status = self._motion = None
        if surface is not None:
            state.z, state.pitch, state.roll = surface.z, surface.pitch, surface.roll
        k = 0
        while k < len(substeps):
            command, substep = substeps[k]
            # A pedal command's pedals do not depend on the state: the substeps it holds
            # for are integrated in one go.
            repeats = 1
            if command.mode == LongitudinalMode.PEDALS:
                while k + repeats < len(substeps) and substeps[k + repeats][0] is command:
                    repeats += 1
            self._pedals = self._pedals_for(command, substep)
            inputs = ActuatorInputs(
                accel_pedal=self._pedals.accel,
                brake_pedal=self._pedals.brake,
                front_steer_target=command.front_steer,
                rear_steer_target=command.rear_steer,
                gear=self.gear,
            )
            advance(self.model, state, inputs, substep, repeats)
            k += repeats

    def _pedals_for(self, command: ControlCommand, dt: float) -> Pedals:
        if command.mode == LongitudinalMode.VELOCITY:
            return self._speed_controller.pedals(command.velocity, self.gear, self._state, dt)
        if command.mode == LongitudinalMode.ACCELERATION:
            return self._acceleration_tracker.pedals(
                command.acceleration, self.gear, self._state, dt
            )
        return Pedals(accel=command.accel, brake=command.brake)

    def status(self) -> VehicleStatus:
        """The vehicle's state after the last step."""
        if self._status is None:
            self._status = self._current_status()
        return self._status

    def motion(self) -> Motion:
        """The pose and motion of the status after the last step, without the rest."""
        if self._motion is None:
            # The state integrates the CG; the rear axle lies b behind it: its velocity
            # lacks the CG's b·r of lateral speed, its acceleration adds b·r²
            # (centripetal) and -b·ṙ (lateral) to the CG's.
            state = self._state
            b = self.model.cg_to_rear_axle
            r = state.yaw_rate
            x = state.x - b * math.cos(state.yaw)
            y = state.y - b * math.sin(state.yaw)
            self._motion = Motion(
                Pose(x, y, state.z, state.roll, state.pitch, state.yaw),
                (state.vx, state.vy - b * r, 0.0),
                (state.ax + b * r * r, state.ay - b * state.yaw_acceleration, 0.0),
            )
        return self._motion

    def _current_status(self) -> VehicleStatus:
        state = self._state
        pose, velocity, acceleration = self.motion()
        return VehicleStatus(
            pose=pose,
            velocity=velocity,
            acceleration=acceleration,
            yaw_rate=state.yaw_rate,
            speed=math.hypot(state.vx, state.vy),
            accel_pedal=self._pedals.accel,
            brake_pedal=self._pedals.brake,
            front_steer=state.front_steer,
            rear_steer=state.rear_steer,
            gear=self.gear,
            wheels=wheel_statuses(self.model, state),
        )
