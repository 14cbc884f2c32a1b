"""What every vehicle kind shares: a command gate read on a clock that a step advances
in equal substeps no longer than max_substep."""

from __future__ import annotations

import math
from collections.abc import Iterator
from typing import Generic, Protocol, TypedDict, TypeVar

from egosim.world.vehicle.control import CommandVerdict
from egosim.world.vehicle.gear import Gear

CommandT = TypeVar("CommandT")


class Gate(Protocol[CommandT]):
    timeout: float | None

    def submit(self, command: CommandT, sim_time: float) -> CommandVerdict: ...

    def active_command(self, sim_time: float) -> CommandT: ...

    def release(self) -> None: ...


class VehicleOptions(TypedDict, total=False):
    """A vehicle constructor's keyword options, as `from_catalogue` passes them on."""

    gear: Gear
    command_timeout: float | None
    max_substep: float


class GatedVehicle(Generic[CommandT]):
    def __init__(self, gate: Gate[CommandT], gear: Gear, max_substep: float) -> None:
        self.gear = gear
        self.sim_time = 0.0
        """Seconds of simulation this vehicle has been stepped through."""
        self.max_substep = max_substep
        self._gate = gate

    @property
    def command_timeout(self) -> float | None:
        """Dead-man timeout, s of simulation time without a command before the vehicle
        brakes; None (the default): the last command holds until the next one."""
        return self._gate.timeout

    @command_timeout.setter
    def command_timeout(self, seconds: float | None) -> None:
        self._gate.timeout = seconds

    def command(self, command: CommandT) -> CommandVerdict:
        """Hand the vehicle a command, received now (at sim_time)."""
        return self._gate.submit(command, self.sim_time)

    def release_command(self) -> None:
        """Drop the command in force (its input stopped driving): brake until the next."""
        self._gate.release()

    def _substeps(self, dt: float) -> Iterator[tuple[CommandT, float]]:
        """The substeps of a step of dt s: the command in force at each and its length;
        the clock moves on as each is taken. A bad dt raises before anything moves."""
        if not dt > 0.0:
            raise ValueError(f"step needs a positive dt, got {dt}")
        count = math.ceil(dt / self.max_substep)
        return self._clocked(count, dt / count)

    def _clocked(self, count: int, substep: float) -> Iterator[tuple[CommandT, float]]:
        for _ in range(count):
            yield self._gate.active_command(self.sim_time), substep
            self.sim_time += substep
