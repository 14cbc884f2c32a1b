"""Time per Vehicle.step(dt) and per Vehicle.status(), for each longitudinal mode.

Usage: .venv/bin/python benchmarks/vehicle_step.py [--dt 0.01] [--steps 20000]
"""

from __future__ import annotations

import argparse
import statistics
import time

from egosim.world.vehicle import ControlCommand, LongitudinalMode, Pose, RoadSurface, Vehicle

COMMANDS = {
    "pedals": ControlCommand(accel=0.3, front_steer=0.05),
    "velocity": ControlCommand(mode=LongitudinalMode.VELOCITY, velocity=15.0, front_steer=0.05),
    "acceleration": ControlCommand(
        mode=LongitudinalMode.ACCELERATION, acceleration=0.5, front_steer=0.05
    ),
}
ROUNDS = 5


def time_steps(command: ControlCommand, dt: float, steps: int) -> tuple[float, float]:
    """Median over ROUNDS of (µs per command+step, µs per status read)."""
    step_us, status_us = [], []
    surface = RoadSurface(z=0.0, pitch=-0.02)
    for _ in range(ROUNDS):
        vehicle = Vehicle.from_catalogue()
        vehicle.teleport(Pose(), speed=10.0)
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
    for name, command in COMMANDS.items():
        step_us, status_us = time_steps(command, args.dt, args.steps)
        print(f"{name:>12}: command+step {step_us:7.1f} µs   status {status_us:6.1f} µs")


if __name__ == "__main__":
    main()
