"""Time per vehicle step(dt) and per status(): the car in each longitudinal mode, the
skid-steer ground vehicle with each command kind.

Usage: .venv/bin/python benchmarks/vehicle_step.py [--dt 0.01] [--steps 20000]
"""

from __future__ import annotations

import argparse
import statistics
import time
from collections.abc import Callable
from typing import Any

from egosim.world.vehicle import (
    BodyVelocityCommand,
    ControlCommand,
    LongitudinalMode,
    Pose,
    RoadSurface,
    SideEffortCommand,
    SkidSteerVehicle,
    Vehicle,
)

GROUND_MODEL = "UGV_6W_Skid_Steer"
ROUNDS = 5


def car() -> Vehicle:
    vehicle = Vehicle.from_catalogue()
    vehicle.teleport(Pose(), speed=10.0)
    return vehicle


def ground_vehicle() -> SkidSteerVehicle:
    vehicle = SkidSteerVehicle.from_catalogue(GROUND_MODEL)
    vehicle.teleport(Pose(), speed=1.0)
    return vehicle


CASES: dict[str, tuple[Callable[[], Any], Any]] = {
    "car, pedals": (car, ControlCommand(accel=0.3, front_steer=0.05)),
    "car, velocity": (
        car,
        ControlCommand(mode=LongitudinalMode.VELOCITY, velocity=15.0, front_steer=0.05),
    ),
    "car, acceleration": (
        car,
        ControlCommand(mode=LongitudinalMode.ACCELERATION, acceleration=0.5, front_steer=0.05),
    ),
    "skid-steer, side efforts": (
        ground_vehicle,
        SideEffortCommand(throttle=0.6, skid_steering=0.2),
    ),
    "skid-steer, body velocity": (ground_vehicle, BodyVelocityCommand(linear=2.0, angular=0.3)),
}


def time_steps(make: Callable[[], Any], command: Any, dt: float, steps: int) -> tuple[float, float]:
    """Median over ROUNDS of (µs per command+step, µs per status read)."""
    step_us, status_us = [], []
    surface = RoadSurface(z=0.0, pitch=-0.02)
    for _ in range(ROUNDS):
        vehicle = make()
        start = time.perf_counter()
        for _ in range(steps):
            vehicle.command(command)
            vehicle.step(dt, surface)
        step_us.append((time.perf_counter() - start) / steps * 1e6)
        start = time.perf_counter()
        for _ in range(steps):
            vehicle.status()
        status_us.append((time.perf_counter() - start) / steps * 1e6)
    return statistics.median(step_us), statistics.median(status_us)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--dt", type=float, default=0.01, help="step length, s")
    parser.add_argument("--steps", type=int, default=20000, help="steps per round")
    args = parser.parse_args()
    print(f"dt = {args.dt} s, {args.steps} steps x {ROUNDS} rounds (median)")
    for name, (make, command) in CASES.items():
        step_us, status_us = time_steps(make, command, args.dt, args.steps)
        print(f"{name:>25}: command+step {step_us:7.1f} µs   status {status_us:6.1f} µs")


if __name__ == "__main__":
    main()
