"""A skid-steer (differential-drive) ground vehicle behind the same interface as Vehicle.

Each side (left, right) is a speed-controlled motor: its ground speed follows
effort · max_track_speed as a first-order lag of time constant
`motor_time_constant`, its rate of change capped at `max_track_accel`. The body
then moves as a differential drive whose turning loses a share to skidding:

    v = (v_l + v_r)/2        ω = η·(v_r − v_l)/B        η = turn_efficiency, B = track width
    ẋ = v·cos ψ              ẏ = v·sin ψ                ψ̇ = ω

so the body never slides sideways (vy = 0) and the skid shows as a wider
effective track B/η.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import TYPE_CHECKING

from egosim.world.vehicle.catalogue import GRAVITY
from egosim.world.vehicle.control import DEFAULT_COMMAND_TIMEOUT
from egosim.world.vehicle.gear import Gear
from egosim.world.vehicle.ground_catalogue import GROUND_VEHICLE_CATALOGUE, GroundVehicleModel
from egosim.world.vehicle.skid_steer_commands import (
    BodyVelocityCommand,
    SkidSteerCommand,
    SkidSteerGate,
)
from egosim.world.vehicle.stepping import GatedVehicle, VehicleOptions
from egosim.world.vehicle.vehicle import (
    DEFAULT_MAX_SUBSTEP,
    Motion,
    Pose,
    RoadSurface,
    VehicleStatus,
)
from egosim.world.vehicle.wheels import Wheels, WheelStatus

if TYPE_CHECKING:
    from typing_extensions import Unpack  # typing's own from Python 3.11

STANDSTILL_SPEED = 0.01
"""A side commanded to stop that is slower than this (m/s) is held at rest, as the
holding brake of a drive controller does; without it the lag would creep forever."""


def side_speed_after(speed: float, target: float, model: GroundVehicleModel, dt: float) -> float:
    """One side's ground speed (m/s) after dt (s) of following target (m/s).

    The lag is integrated exactly, so any dt is stable; the change is then capped
    at max_track_accel · dt.
    """
    change = (target - speed) * -math.expm1(-dt / model.motor_time_constant)
    limit = model.max_track_accel * dt
    after = speed + min(max(change, -limit), limit)
    return 0.0 if target == 0.0 and abs(after) < STANDSTILL_SPEED else after


class SkidSteerVehicle(GatedVehicle[SkidSteerCommand]):
    """One skid-steer vehicle of a ground vehicle model; advanced by step(dt)."""

    def __init__(
        self,
        model: GroundVehicleModel,
        pose: Pose | None = None,
        *,
        gear: Gear = Gear.DRIVE,
        command_timeout: float | None = DEFAULT_COMMAND_TIMEOUT,
        max_substep: float = DEFAULT_MAX_SUBSTEP,
    ) -> None:
        super().__init__(SkidSteerGate(command_timeout), gear, max_substep)
        self.model = model
        self._pose = Pose()
        self._left = self._right = 0.0
        self._speed_rate = 0.0
        self._accel_pedal = 0.0
        self._brake_pedal = 1.0
        self.teleport(pose or Pose())

    @classmethod
    def from_catalogue(
        cls, name: str, pose: Pose | None = None, **options: Unpack[VehicleOptions]
    ) -> SkidSteerVehicle:
        """A vehicle of the ground vehicle model `name`; options as for the constructor."""
        return cls(GROUND_VEHICLE_CATALOGUE[name], pose, **options)

    def set_gear(self, gear: Gear) -> None:
        """P and N leave the motors without drive (the sides are brought to rest); R and D
        drive as commanded (the command's sign chooses the direction)."""
        self.gear = gear

    def teleport(
        self, pose: Pose, speed: float = 0.0, front_steer: float = 0.0, rear_steer: float = 0.0
    ) -> None:
        """Put the vehicle at pose, moving straight at speed (m/s, body x).

        The wheel angles exist for the Vehicle interface; a skid-steer has none to set.
        """
        self._pose = pose
        self._left = self._right = speed
        self._speed_rate = 0.0

    def shove(self, displacement: tuple[float, float], change: tuple[float, float]) -> None:
        """A contact's response: move by `displacement` (m) and change the forward speed
        by the forward part of `change` (m/s), both in the map frame; tracks do not slide
        sideways."""
        pose = self._pose
        forward = change[0] * math.cos(pose.yaw) + change[1] * math.sin(pose.yaw)
        self._left += forward
        self._right += forward
        self._pose = replace(pose, x=pose.x + displacement[0], y=pose.y + displacement[1])

    def step(self, dt: float, surface: RoadSurface | None = None) -> None:
        """Advance dt seconds; surface, when given, is the ground under the vehicle now."""
        substeps = self._substeps(dt)
        pose = self._pose
        if surface is not None:
            pose = Pose(pose.x, pose.y, surface.z, surface.roll, surface.pitch, pose.yaw)
        for command, substep in substeps:
            pose = self._advance(pose, command, substep)
        self._pose = pose

    def _advance(self, pose: Pose, command: SkidSteerCommand, dt: float) -> Pose:
        model = self.model
        if isinstance(command, BodyVelocityCommand):
            left_effort, right_effort = command.side_efforts(model)
            self._accel_pedal, self._brake_pedal = abs(left_effort + right_effort) / 2.0, 0.0
        else:
            left_effort, right_effort = command.side_efforts()
            self._accel_pedal, self._brake_pedal = abs(command.throttle), command.brake
        if self.gear.drive_direction == 0:
            left_effort = right_effort = 0.0
        speed_before = self.forward_speed
        self._left = side_speed_after(self._left, left_effort * model.max_track_speed, model, dt)
        self._right = side_speed_after(self._right, right_effort * model.max_track_speed, model, dt)
        speed = self.forward_speed
        self._speed_rate = (speed - speed_before) / dt
        # Midpoint heading: exact for a constant-speed arc within the step.
        yaw_change = dt * self.yaw_rate * math.cos(pose.roll) / math.cos(pose.pitch)
        heading = pose.yaw + yaw_change / 2.0
        level_speed = speed * math.cos(pose.pitch)
        return Pose(
            x=pose.x + dt * level_speed * math.cos(heading),
            y=pose.y + dt * level_speed * math.sin(heading),
            z=pose.z - dt * speed * math.sin(pose.pitch),
            roll=pose.roll,
            pitch=pose.pitch,
            yaw=math.remainder(pose.yaw + yaw_change, math.tau),
        )

    @property
    def side_speeds(self) -> tuple[float, float]:
        """(left, right) ground speeds of the two sides, m/s."""
        return self._left, self._right

    @property
    def forward_speed(self) -> float:
        """Body x velocity, m/s."""
        return (self._left + self._right) / 2.0

    @property
    def yaw_rate(self) -> float:
        """rad/s, counter-clockwise positive."""
        return (self._right - self._left) / self.model.effective_track_width

    def motion(self) -> Motion:
        """The pose and motion of the status, without the rest."""
        speed = self.forward_speed
        return Motion(self._pose, (speed, 0.0, 0.0), (self._speed_rate, speed * self.yaw_rate, 0.0))

    def status(self) -> VehicleStatus:
        """The vehicle's state after the last step; wheels carry only their static loads."""
        speed, yaw_rate = self.forward_speed, self.yaw_rate
        share = self.model.mass * GRAVITY / 4.0
        wheel = WheelStatus(
            lateral_force=0.0, slip_angle=0.0, cornering_stiffness=0.0, vertical_load=share
        )
        pose, velocity, acceleration = self.motion()
        return VehicleStatus(
            pose=pose,
            velocity=velocity,
            acceleration=acceleration,
            yaw_rate=yaw_rate,
            speed=abs(speed),
            accel_pedal=self._accel_pedal,
            brake_pedal=self._brake_pedal,
            front_steer=0.0,
            rear_steer=0.0,
            gear=self.gear,
            wheels=Wheels(wheel, wheel, wheel, wheel),
        )
