"""Control commands as CtrlCmd defines them, and the gate that validates them.

The gate clamps out-of-range values, rejects a command carrying NaN or an
infinity (keeping the last valid one) and holds the last valid command until the
next one, as a simulator reading the latest value each frame does. Before the
first command the brake is held. An optional dead-man `timeout` falls back to a
safe brake when no command has arrived for that many seconds of simulation time.
It reads no clock: the caller passes the simulation time.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields, replace
from enum import IntEnum

from egosim.world.vehicle.catalogue import VehicleModel

DEFAULT_COMMAND_TIMEOUT: float | None = None
"""Seconds of silence after which the gate brakes the car; None: the last command holds."""


class LongitudinalMode(IntEnum):
    """CtrlCmd.longlCmdType.

    UNSET is the field's default: a client that fills only accel, brake and steering
    (MORAI's own driving example does) leaves it 0, and MORAI SIM drives such a
    command by its pedals, so the gate reads it as PEDALS.
    """

    UNSET = 0
    PEDALS = 1
    VELOCITY = 2
    ACCELERATION = 3


@dataclass(frozen=True)
class ControlCommand:
    """One CtrlCmd in SI units."""

    mode: int = LongitudinalMode.PEDALS
    """A LongitudinalMode value; anything else is rejected by the gate."""
    accel: float = 0.0
    """Accelerator pedal 0..1 (PEDALS mode)."""
    brake: float = 0.0
    """Brake pedal 0..1 (PEDALS mode)."""
    front_steer: float = 0.0
    """Front road-wheel angle, rad, positive to the left."""
    rear_steer: float = 0.0
    """Rear road-wheel angle, rad, positive to the left."""
    velocity: float = 0.0
    """Target speed in the direction the gear drives, m/s (VELOCITY mode)."""
    acceleration: float = 0.0
    """Target rate of change of that speed, m/s² (ACCELERATION mode)."""


@dataclass(frozen=True)
class CommandVerdict:
    """What the gate did with a command."""

    accepted: bool
    reason: str = ""
    """Why it was rejected; empty when accepted."""
    clamped: tuple[str, ...] = ()
    """Fields brought into range."""


def command_timed_out(received_at: float | None, timeout: float | None, sim_time: float) -> bool:
    """Whether a gate that last took a command at `received_at` (None: never) falls back
    to its safe command at `sim_time`, with dead-man `timeout` s (None: never)."""
    if received_at is None:
        return True
    return timeout is not None and sim_time - received_at > timeout


SAFE_BRAKE = ControlCommand(mode=LongitudinalMode.PEDALS, brake=1.0)


class CommandGate:
    """Holds the command in force for a vehicle model."""

    def __init__(
        self, model: VehicleModel, timeout: float | None = DEFAULT_COMMAND_TIMEOUT
    ) -> None:
        self._ranges = {
            "accel": (0.0, 1.0),
            "brake": (0.0, 1.0),
            "front_steer": (-model.max_steer_front, model.max_steer_front),
            "rear_steer": (-model.max_steer_rear, model.max_steer_rear),
            "velocity": (0.0, math.inf),
        }
        self.timeout = timeout
        self._command = SAFE_BRAKE
        self._received_at: float | None = None
        self._held: ControlCommand | None = None
        self._brake = (SAFE_BRAKE, SAFE_BRAKE)
        """The last command in force and the full brake holding its steering (asked for
        at every substep while the gate has timed out)."""

    def submit(self, command: ControlCommand, sim_time: float) -> CommandVerdict:
        """Accept `command` at sim_time (s), clamped into range, unless it is invalid."""
        non_finite = [
            f.name for f in fields(command) if not math.isfinite(getattr(command, f.name))
        ]
        if non_finite:
            return CommandVerdict(False, reason=f"non-finite {', '.join(non_finite)}")
        if command.mode not in LongitudinalMode.__members__.values():
            return CommandVerdict(False, reason=f"unknown longitudinal mode {command.mode}")
        changes = {}
        for name, (low, high) in self._ranges.items():
            value = getattr(command, name)
            if not low <= value <= high:
                changes[name] = min(max(value, low), high)
        mode = LongitudinalMode(command.mode)
        if mode is LongitudinalMode.UNSET:
            mode = LongitudinalMode.PEDALS
        self._command = replace(command, mode=mode, **changes)
        self._received_at = sim_time
        self._held = None
        return CommandVerdict(True, clamped=tuple(changes))

    def hold(self, command: ControlCommand) -> None:
        """A command of the simulator's own (a scenario's initial speed) in force until
        the first one submitted; no dead-man timeout runs on it, as no input sent it."""
        self._held = command
        self._received_at = None

    def release(self) -> None:
        """Forget the command in force: the brake is held, steering kept, until the next."""
        self._received_at = None
        self._held = None

    def timed_out(self, sim_time: float) -> bool:
        """True before the first command and, with a dead-man timeout, after `timeout` s
        without one."""
        return command_timed_out(self._received_at, self.timeout, sim_time)

    def active_command(self, sim_time: float) -> ControlCommand:
        """The command in force: one held, the last valid one, or a full brake with the
        steering held."""
        if self._held is not None:
            return self._held
        if self.timed_out(sim_time):
            last = self._command
            if self._brake[0] is not last:
                brake = replace(
                    SAFE_BRAKE, front_steer=last.front_steer, rear_steer=last.rear_steer
                )
                self._brake = (last, brake)
            return self._brake[1]
        return self._command
