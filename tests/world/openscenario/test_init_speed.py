"""An ego its stack drives starts at the scenario's Init speed and keeps it until the
stack's first command (the scenario's test driver hands over); the dead-man timeout
runs from that command on, not before the stack has spoken."""

from __future__ import annotations

import pytest
from tests.world.openscenario.stories import (
    init_speed,
    lane,
    scenario,
    start_world,
    step,
    teleport,
    vehicle,
)

from egosim.world.vehicle import ControlCommand, Gear, LongitudinalMode


def stack_driven(speed: float, timeout: float | None):  # type: ignore[no-untyped-def]
    text = scenario(vehicle("Ego"), teleport("Ego", lane(100)) + init_speed("Ego", speed))
    world, run = start_world(text, drives_ego=False)
    world.command_timeout_s = timeout
    return world, run, world.egos[0].vehicle


@pytest.mark.parametrize("timeout", [None, 0.5])
def test_the_init_speed_holds_until_the_stack_speaks_whatever_the_dead_man_timeout(
    timeout: float | None,
) -> None:
    world, run, ego = stack_driven(15.0, timeout)
    step(world, run, 3.0, drives_ego=False)
    assert ego.status().velocity[0] == pytest.approx(15.0, abs=0.05)


def test_the_stacks_first_command_takes_over_and_starts_the_dead_man_timeout() -> None:
    world, run, ego = stack_driven(15.0, 0.5)
    step(world, run, 1.0, drives_ego=False)
    ego.command(ControlCommand(mode=LongitudinalMode.PEDALS, accel=0.0, brake=0.0))
    step(world, run, 0.4, drives_ego=False)
    coasting = ego.status().velocity[0]
    assert 14.0 < coasting < 15.0  # drag and rolling resistance, no hold any more
    step(world, run, 1.6, drives_ego=False)  # 0.5 s without a command: the brake
    assert ego.status().velocity[0] < coasting - 5.0


def test_a_negative_init_speed_is_held_in_reverse() -> None:
    world, run, ego = stack_driven(-1.5, None)
    step(world, run, 2.0, drives_ego=False)
    assert ego.gear is Gear.REVERSE
    assert ego.status().velocity[0] == pytest.approx(-1.5, abs=0.05)
