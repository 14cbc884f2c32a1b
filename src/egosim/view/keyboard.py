"""Keyboard driving: held keys -> pedals, steering and gear, as MORAI's keyboard control
mode (EventInfo ctrl_mode 1) drives an ego from the arrow keys.

The page sends the keys it holds about ten times a second while it drives; each message
becomes a CtrlCmd-like command, which holds until the next one. When messages stop for
KEY_SILENCE_S (page closed, tab hidden) the view brakes the ego fully: a vanished
browser never leaves a throttle held.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..world.vehicle import ControlCommand, Gear, Vehicle

THROTTLE_PEDAL = 0.6
BRAKE_PEDAL = 0.8
#: Fraction of the model's maximum road-wheel angle a held arrow key steers to.
STEER_REACH = 0.7
#: Seconds a held key takes to steer from centre to its reach; released, the wheel
#: returns twice as fast.
STEER_RAMP_S = 0.8
#: Below this speed (m/s) holding brake selects reverse, and holding throttle in
#: reverse selects drive again.
SHIFT_SPEED_MPS = 0.3
#: Longest time (s) one message's steering may move the wheel for.
MAX_KEY_INTERVAL_S = 0.2
#: Simulation time (s) without a key message after which the page counts as gone.
KEY_SILENCE_S = 0.5


@dataclass(frozen=True)
class HeldKeys:
    """Keys held: throttle (up / W), brake (down / S), left (left / A), right (right / D)."""

    throttle: bool = False
    brake: bool = False
    left: bool = False
    right: bool = False


class KeyboardDriver:
    """Turns the held keys of one ego into commands; keeps the steering wheel's angle."""

    def __init__(self) -> None:
        self.steer = 0.0
        self._last_time: float | None = None

    def drive(self, vehicle: Vehicle, keys: HeldKeys) -> None:
        """Command `vehicle` (loop thread) for the keys held now."""
        now = vehicle.sim_time
        interval = 0.0 if self._last_time is None else now - self._last_time
        self._last_time = now
        self._turn(vehicle, keys, min(max(interval, 0.0), MAX_KEY_INTERVAL_S))
        speed = vehicle.status().speed
        forward, backward = keys.throttle, keys.brake
        if vehicle.gear is Gear.REVERSE:
            forward, backward = backward, forward  # in reverse, "down" drives backwards
        if speed < SHIFT_SPEED_MPS:
            if keys.brake and not keys.throttle and vehicle.gear is Gear.DRIVE:
                vehicle.set_gear(Gear.REVERSE)
                forward, backward = True, False
            elif keys.throttle and not keys.brake and vehicle.gear is not Gear.DRIVE:
                vehicle.set_gear(Gear.DRIVE)
                forward, backward = True, False
        vehicle.command(
            ControlCommand(
                accel=THROTTLE_PEDAL if forward and not backward else 0.0,
                brake=BRAKE_PEDAL if backward else 0.0,
                front_steer=self.steer,
            )
        )

    def silent(self, vehicle: Vehicle) -> bool:
        """No key message for KEY_SILENCE_S of simulation time."""
        return self._last_time is not None and vehicle.sim_time - self._last_time > KEY_SILENCE_S

    def release(self, vehicle: Vehicle) -> None:
        """The page has gone: a full brake, the wheel where it is."""
        vehicle.command(ControlCommand(accel=0.0, brake=1.0, front_steer=self.steer))

    def _turn(self, vehicle: Vehicle, keys: HeldKeys, interval: float) -> None:
        reach = vehicle.model.max_steer_front * STEER_REACH
        target = reach * (int(keys.left) - int(keys.right))
        rate = reach / STEER_RAMP_S * (1.0 if target else 2.0)
        change = max(min(target - self.steer, rate * interval), -rate * interval)
        self.steer += change
