"""Command gate: clamping, rejection of non-finite values, holding, dead-man timeout."""

from __future__ import annotations

import math

import pytest

from egosim.world.vehicle import CommandGate, ControlCommand, LongitudinalMode, Pose, Vehicle


def test_out_of_range_values_are_clamped_and_reported(drive, niro) -> None:
    command = ControlCommand(accel=1.7, brake=-0.2, front_steer=2.0, rear_steer=0.3)
    verdict = niro.command(command)
    assert verdict.accepted
    assert set(verdict.clamped) == {"accel", "brake", "front_steer", "rear_steer"}
    *_, status = drive(niro, command, seconds=3.0)
    assert (status.accel_pedal, status.brake_pedal) == (1.0, 0.0)
    assert status.front_steer == pytest.approx(niro.model.max_steer_front)
    assert status.rear_steer == 0.0  # the Niro does not steer its rear wheels


def test_negative_target_speed_is_clamped_to_standstill(niro) -> None:
    verdict = niro.command(ControlCommand(mode=LongitudinalMode.VELOCITY, velocity=-5.0))
    assert verdict.accepted
    assert verdict.clamped == ("velocity",)


@pytest.mark.parametrize("field", ["accel", "brake", "front_steer", "velocity", "acceleration"])
@pytest.mark.parametrize("value", [math.nan, math.inf, -math.inf])
def test_non_finite_command_is_rejected_and_the_last_valid_one_kept(niro, field, value) -> None:
    assert niro.command(ControlCommand(accel=0.4, front_steer=0.1)).accepted
    verdict = niro.command(ControlCommand(**{field: value}))
    assert not verdict.accepted
    assert field in verdict.reason
    for _ in range(10):
        niro.step(0.01)
    status = niro.status()
    assert status.accel_pedal == 0.4
    assert status.front_steer > 0.0
    assert all(math.isfinite(component) for component in status.velocity)


@pytest.mark.parametrize("mode", [7, 4, -1])
def test_unknown_mode_is_rejected(niro, mode) -> None:
    verdict = niro.command(ControlCommand(mode=mode))
    assert not verdict.accepted
    assert str(mode) in verdict.reason


def test_an_unset_mode_drives_by_the_pedals(drive, niro) -> None:
    """MORAI's example client fills accel, brake and steering only: longlCmdType 0."""
    command = ControlCommand(mode=LongitudinalMode.UNSET, accel=0.5, front_steer=0.05)
    assert niro.command(command).accepted
    *_, status = drive(niro, command, seconds=2.0)
    assert (status.accel_pedal, status.brake_pedal) == (0.5, 0.0)
    assert status.speed > 3.0


def test_a_single_command_holds_until_the_next_one() -> None:
    vehicle = Vehicle.from_catalogue()
    assert vehicle.command_timeout is None
    vehicle.command(ControlCommand(mode=LongitudinalMode.VELOCITY, velocity=30 / 3.6))
    for _ in range(2000):
        vehicle.step(0.01)
    status = vehicle.status()
    assert status.brake_pedal < 0.5
    assert status.speed == pytest.approx(30 / 3.6, abs=0.3)
    vehicle.command(ControlCommand(brake=1.0))
    for _ in range(500):
        vehicle.step(0.01)
    assert vehicle.status().speed == 0.0


def test_no_command_yet_means_held_brakes(niro) -> None:
    niro.step(0.1)
    assert niro.status().brake_pedal == 1.0


def test_silence_longer_than_the_timeout_brakes_to_a_stop_holding_the_steering() -> None:
    vehicle = Vehicle.from_catalogue(command_timeout=0.5)
    vehicle.teleport(Pose(), speed=15.0)
    vehicle.command(ControlCommand(accel=0.3, front_steer=0.02))
    for _ in range(50):
        vehicle.step(0.01)
    assert vehicle.status().accel_pedal == 0.3
    vehicle.step(0.01)
    status = vehicle.status()
    assert (status.accel_pedal, status.brake_pedal) == (0.0, 1.0)
    for _ in range(500):
        vehicle.step(0.01)
    status = vehicle.status()
    assert status.speed == 0.0
    assert status.front_steer == pytest.approx(0.02)
    assert vehicle.command(ControlCommand(accel=0.3)).accepted
    vehicle.step(0.01)
    assert vehicle.status().brake_pedal == 0.0


def test_gate_times_out_only_after_the_configured_silence(niro) -> None:
    gate = CommandGate(niro.model, timeout=0.5)
    assert gate.timed_out(0.0)
    command = ControlCommand(accel=0.2, front_steer=0.1, rear_steer=0.0)
    gate.submit(command, sim_time=10.0)
    assert gate.active_command(10.5) == command
    assert gate.timed_out(10.51)
    assert gate.active_command(10.51) == ControlCommand(brake=1.0, front_steer=0.1)


def test_velocity_mode_with_zero_target_stops_and_holds(drive, niro) -> None:
    niro.teleport(Pose(), speed=10.0)
    command = ControlCommand(mode=LongitudinalMode.VELOCITY, velocity=0.0)
    statuses = list(drive(niro, command, seconds=30.0))
    assert all(status.velocity[0] >= 0.0 for status in statuses)
    assert statuses[-1].speed == 0.0
    assert all(0.0 <= status.brake_pedal <= 1.0 for status in statuses)
