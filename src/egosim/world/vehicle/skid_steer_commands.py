"""Commands a skid-steer vehicle takes, and the gate that validates them.

Two kinds: direct side efforts (GVDirectCmd: throttle and skid steering) and
body velocity targets (GVStateCmd, Twist). The gate clamps out-of-range values,
rejects a command carrying NaN or an infinity (keeping the last valid one) and
holds the last valid command until the next one; before the first command, and
with the optional dead-man `timeout` after that many seconds of simulation time
without one, the vehicle stops. It reads no clock: the caller passes the
simulation time.
"""

from __future__ import annotations

import math
from dataclasses import astuple, dataclass

from egosim.world.vehicle.control import (
    DEFAULT_COMMAND_TIMEOUT,
    CommandVerdict,
    command_timed_out,
)
from egosim.world.vehicle.ground_catalogue import GroundVehicleModel


@dataclass(frozen=True)
class SideEffortCommand:
    """Direct drive: motor efforts of the two sides, mixed from throttle and skid steering."""

    throttle: float = 0.0
    """-1..1: forward (+) or backward (-) share of the top speed."""
    skid_steering: float = 0.0
    """-1..1: positive turns left (counter-clockwise), as REP 103 yaw."""
    brake: float = 0.0
    """0..1: scales both sides' drive down to a stop at 1."""

    def side_efforts(self) -> tuple[float, float]:
        """(left, right) motor efforts, -1..1.

        Left = throttle - skid, right = throttle + skid; when one side would exceed
        full effort both are scaled by the same factor, so the turn keeps its radius.
        """
        left = self.throttle - self.skid_steering
        right = self.throttle + self.skid_steering
        drive = (1.0 - self.brake) / max(1.0, abs(left), abs(right))
        return left * drive, right * drive


@dataclass(frozen=True)
class BodyVelocityCommand:
    """State control: target forward speed and yaw rate of the body."""

    linear: float = 0.0
    """m/s along body x (negative: backwards)."""
    angular: float = 0.0
    """rad/s about body z, counter-clockwise positive."""

    def side_efforts(self, model: GroundVehicleModel) -> tuple[float, float]:
        """(left, right) efforts whose steady state is this motion.

        A target one side cannot reach scales both sides by the same factor: the
        vehicle keeps the commanded curvature at a lower speed.
        """
        half_track = model.effective_track_width / 2.0
        top = model.max_track_speed
        left = (self.linear - self.angular * half_track) / top
        right = (self.linear + self.angular * half_track) / top
        scale = max(1.0, abs(left), abs(right))
        return left / scale, right / scale


SkidSteerCommand = SideEffortCommand | BodyVelocityCommand

STOP = SideEffortCommand(brake=1.0)

_SIDE_EFFORT_RANGES = {"throttle": (-1.0, 1.0), "skid_steering": (-1.0, 1.0), "brake": (0.0, 1.0)}


class SkidSteerGate:
    """Holds the command in force for a skid-steer vehicle."""

    def __init__(self, timeout: float | None = DEFAULT_COMMAND_TIMEOUT) -> None:
        self.timeout = timeout
        self._command: SkidSteerCommand = STOP
        self._received_at: float | None = None

    def submit(self, command: SkidSteerCommand, sim_time: float) -> CommandVerdict:
        """Accept `command` at sim_time (s), clamped into range, unless it is invalid."""
        if not isinstance(command, SideEffortCommand | BodyVelocityCommand):
            return CommandVerdict(False, reason=f"a skid-steer takes no {type(command).__name__}")
        if not all(math.isfinite(value) for value in astuple(command)):
            return CommandVerdict(False, reason="non-finite value")
        clamped: tuple[str, ...] = ()
        if isinstance(command, SideEffortCommand):
            values = {
                name: min(max(getattr(command, name), low), high)
                for name, (low, high) in _SIDE_EFFORT_RANGES.items()
            }
            clamped = tuple(name for name in values if values[name] != getattr(command, name))
            command = SideEffortCommand(**values)
        self._command = command
        self._received_at = sim_time
        return CommandVerdict(True, clamped=clamped)

    def release(self) -> None:
        """Forget the command in force: the vehicle stops until the next one."""
        self._received_at = None

    def timed_out(self, sim_time: float) -> bool:
        """True before the first command and, with a dead-man timeout, after `timeout` s
        without one."""
        return command_timed_out(self._received_at, self.timeout, sim_time)

    def active_command(self, sim_time: float) -> SkidSteerCommand:
        """The command in force: the last valid one, or STOP before any or after a timeout."""
        return STOP if self.timed_out(sim_time) else self._command
