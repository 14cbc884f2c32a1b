"""Time per SkidSteerVehicle.step(dt) and per status(), for each command kind.

Usage: .venv/bin/python benchmarks/skid_steer_step.py [--dt 0.01] [--steps 20000]
"""

from __future__ import annotations

import argparse
import statistics
import time

from egosim.world.vehicle import (
    BodyVelocityCommand,
    Pose,
    RoadSurface,
    SideEffortCommand,
    SkidSteerVehicle,
)

COMMANDS = {
    "side efforts": SideEffortCommand(throttle=0.6, skid_steering=0.2),
    "body velocity": BodyVelocityCommand(linear=2.0, angular=0.3),
}
MODEL = "UGV_6W_Skid_Steer"
ROUNDS = 5


def time_steps(
    command: SideEffortCommand | BodyVelocityCommand, dt: float, steps: int
) -> tuple[float, float]:
    """Median over ROUNDS of (µs per command+step, µs per status read)."""
    step_us, status_us = [], []
    surface = RoadSurface(z=0.0, pitch=-0.02)
    for _ in range(ROUNDS):
        vehicle = SkidSteerVehicle.from_catalogue(MODEL)
        vehicle.teleport(Pose(), speed=1.0)
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
    print(f"{MODEL}, dt = {args.dt} s, {args.steps} steps x {ROUNDS} rounds (median)")
    for name, command in COMMANDS.items():
        step_us, status_us = time_steps(command, args.dt, args.steps)
        print(f"{name:>13}: command+step {step_us:7.1f} µs   status {status_us:6.1f} µs")


if __name__ == "__main__":
    main()
