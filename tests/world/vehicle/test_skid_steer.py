"""Skid-steer ground vehicles against closed forms: side motor response, differential
drive kinematics, curvature-preserving saturation, gears, timeout and validation."""

from __future__ import annotations

import math

import pytest
from tests.world.vehicle.driving import STEP, drive

from egosim.world.vehicle import (
    GROUND_VEHICLE_CATALOGUE,
    BodyVelocityCommand,
    ControlCommand,
    Gear,
    Pose,
    RoadSurface,
    SideEffortCommand,
    SkidSteerVehicle,
)

ROBOT = "WeBOT_Indoor_Robot"
UGV = "UGV_6W_Skid_Steer"


def settle(vehicle: SkidSteerVehicle, command: SideEffortCommand | BodyVelocityCommand) -> None:
    """Hold `command` long enough (many motor time constants) for steady state."""
    for _ in drive(vehicle, command, 10.0):
        pass


def test_throttle_gives_its_share_of_top_speed_straight_ahead() -> None:
    robot = SkidSteerVehicle.from_catalogue(ROBOT, Pose(x=1.0, y=2.0, yaw=0.5))
    settle(robot, SideEffortCommand(throttle=0.6))
    status = robot.status()
    assert status.velocity[0] == pytest.approx(0.6 * 1.5, abs=1e-6)
    assert status.yaw_rate == pytest.approx(0.0, abs=1e-12)
    assert status.pose.yaw == pytest.approx(0.5)
    # It moved along its heading only.
    dx, dy = status.pose.x - 1.0, status.pose.y - 2.0
    assert math.atan2(dy, dx) == pytest.approx(0.5)
    assert status.accel_pedal == pytest.approx(0.6)
    assert status.brake_pedal == 0.0


def test_negative_throttle_drives_backwards() -> None:
    robot = SkidSteerVehicle.from_catalogue(ROBOT)
    settle(robot, SideEffortCommand(throttle=-0.4))
    status = robot.status()
    assert status.velocity[0] == pytest.approx(-0.6, abs=1e-6)
    assert status.speed == pytest.approx(0.6, abs=1e-6)
    assert status.pose.x < 0.0
    assert status.accel_pedal == pytest.approx(0.4)


def test_skid_steering_alone_spins_in_place_counter_clockwise() -> None:
    model = GROUND_VEHICLE_CATALOGUE[ROBOT]
    robot = SkidSteerVehicle(model)
    settle(robot, SideEffortCommand(skid_steering=0.5))
    status = robot.status()
    # Sides at -0.75 and +0.75 m/s; yaw rate η·(v_r - v_l)/B.
    expected = model.turn_efficiency * 1.5 / model.track_width
    assert status.yaw_rate == pytest.approx(expected, rel=1e-6)
    assert status.velocity[0] == pytest.approx(0.0, abs=1e-12)
    assert math.hypot(status.pose.x, status.pose.y) < 1e-9
    assert robot.side_speeds == pytest.approx((-0.75, 0.75), abs=1e-6)


def test_negative_skid_steering_turns_clockwise() -> None:
    robot = SkidSteerVehicle.from_catalogue(ROBOT)
    settle(robot, SideEffortCommand(throttle=0.5, skid_steering=-0.2))
    assert robot.status().yaw_rate < 0.0
    assert robot.side_speeds[0] > robot.side_speeds[1]


def test_mixing_beyond_full_effort_keeps_the_turn_radius() -> None:
    robot = SkidSteerVehicle.from_catalogue(ROBOT)
    settle(robot, SideEffortCommand(throttle=1.0, skid_steering=0.5))
    # Unsaturated mix 0.5 / 1.5 scaled by 1/1.5: left 1/3, right full speed.
    left, right = robot.side_speeds
    assert right == pytest.approx(1.5, abs=1e-6)
    assert left == pytest.approx(0.5, abs=1e-6)


def test_body_velocity_target_is_reached_and_drives_a_circle_of_radius_v_over_omega() -> None:
    ugv = SkidSteerVehicle.from_catalogue(UGV)
    command = BodyVelocityCommand(linear=2.0, angular=0.4)
    settle(ugv, command)
    status = ugv.status()
    assert status.velocity[0] == pytest.approx(2.0, abs=1e-6)
    assert status.yaw_rate == pytest.approx(0.4, abs=1e-6)
    assert status.acceleration[1] == pytest.approx(2.0 * 0.4, abs=1e-5)
    assert status.velocity[1] == 0.0
    # A steady arc: the centre lies R = v/ω to the left; every later point is R from it.
    radius = 2.0 / 0.4
    yaw = status.pose.yaw
    centre = (status.pose.x - radius * math.sin(yaw), status.pose.y + radius * math.cos(yaw))
    for later in drive(ugv, command, 10.0):
        distance = math.hypot(later.pose.x - centre[0], later.pose.y - centre[1])
        assert distance == pytest.approx(radius, rel=1e-6)


def test_body_velocity_beyond_the_motors_keeps_the_curvature_at_top_side_speed() -> None:
    model = GROUND_VEHICLE_CATALOGUE[UGV]
    ugv = SkidSteerVehicle(model)
    settle(ugv, BodyVelocityCommand(linear=10.0, angular=1.0))
    status = ugv.status()
    assert status.velocity[0] / status.yaw_rate == pytest.approx(10.0, rel=1e-6)
    assert max(ugv.side_speeds) == pytest.approx(model.max_track_speed, abs=1e-6)


def test_from_rest_the_sides_accelerate_at_their_limit() -> None:
    model = GROUND_VEHICLE_CATALOGUE[UGV]
    ugv = SkidSteerVehicle(model)
    statuses = list(drive(ugv, SideEffortCommand(throttle=1.0), 1.0))
    # The lag asks for 5 m/s / 0.3 s ≈ 16.7 m/s²; the motors give max_track_accel until
    # the lag asks for less (above 5 - 0.3·2 = 4.4 m/s).
    assert statuses[-1].velocity[0] == pytest.approx(model.max_track_accel * 1.0, rel=1e-9)
    assert statuses[-1].acceleration[0] == pytest.approx(model.max_track_accel, rel=1e-9)


def test_small_commands_follow_the_first_order_motor_lag() -> None:
    model = GROUND_VEHICLE_CATALOGUE[ROBOT]
    robot = SkidSteerVehicle(model)
    target = 0.05 * model.max_track_speed
    tau = model.motor_time_constant
    for k, status in enumerate(drive(robot, SideEffortCommand(throttle=0.05), 0.5), start=1):
        t = k * STEP
        assert status.velocity[0] == pytest.approx(target * (1 - math.exp(-t / tau)), rel=1e-9)


def test_brake_scales_the_drive_down_to_a_stop() -> None:
    robot = SkidSteerVehicle.from_catalogue(ROBOT)
    settle(robot, SideEffortCommand(throttle=1.0, brake=0.5))
    assert robot.status().velocity[0] == pytest.approx(0.75, abs=1e-6)
    settle(robot, SideEffortCommand(throttle=1.0, brake=1.0))
    status = robot.status()
    assert status.speed == 0.0
    assert (status.accel_pedal, status.brake_pedal) == (1.0, 1.0)


def test_a_command_holds_through_silence() -> None:
    robot = SkidSteerVehicle.from_catalogue(ROBOT)
    settle(robot, SideEffortCommand(throttle=1.0))
    speed = robot.status().speed
    for _ in range(300):
        robot.step(STEP)
    status = robot.status()
    assert status.speed == pytest.approx(speed)
    assert (status.accel_pedal, status.brake_pedal) == (1.0, 0.0)


def test_silence_past_the_dead_man_timeout_stops_the_vehicle_with_the_brake_reported() -> None:
    robot = SkidSteerVehicle.from_catalogue(ROBOT, command_timeout=0.5)
    settle(robot, SideEffortCommand(throttle=1.0))
    for _ in range(300):
        robot.step(STEP)
    status = robot.status()
    assert status.speed == 0.0
    assert (status.accel_pedal, status.brake_pedal) == (0.0, 1.0)


def test_a_new_vehicle_waits_for_a_command() -> None:
    robot = SkidSteerVehicle.from_catalogue(ROBOT)
    robot.step(1.0)
    assert robot.status().pose == Pose()


@pytest.mark.parametrize("gear", [Gear.PARKING, Gear.NEUTRAL])
def test_parking_and_neutral_leave_the_motors_without_drive(gear: Gear) -> None:
    robot = SkidSteerVehicle.from_catalogue(ROBOT, gear=gear)
    settle(robot, SideEffortCommand(throttle=1.0, skid_steering=0.3))
    status = robot.status()
    assert status.pose == Pose()
    assert status.gear == gear


def test_reverse_gear_drives_as_commanded() -> None:
    robot = SkidSteerVehicle.from_catalogue(ROBOT)
    robot.set_gear(Gear.REVERSE)
    settle(robot, BodyVelocityCommand(linear=0.5))
    assert robot.status().velocity[0] == pytest.approx(0.5, abs=1e-6)


def test_non_finite_commands_are_rejected_and_the_last_valid_one_kept() -> None:
    robot = SkidSteerVehicle.from_catalogue(ROBOT)
    assert robot.command(BodyVelocityCommand(linear=1.0)).accepted
    verdict = robot.command(BodyVelocityCommand(linear=math.nan))
    assert not verdict.accepted
    assert "non-finite" in verdict.reason
    assert not robot.command(SideEffortCommand(throttle=math.inf)).accepted
    for _ in range(40):
        robot.step(STEP)
    assert robot.status().velocity[0] > 0.0


def test_out_of_range_efforts_are_clamped_and_named() -> None:
    robot = SkidSteerVehicle.from_catalogue(ROBOT)
    verdict = robot.command(SideEffortCommand(throttle=2.0, skid_steering=-3.0, brake=-1.0))
    assert verdict.accepted
    assert set(verdict.clamped) == {"throttle", "skid_steering", "brake"}


def test_a_ctrl_cmd_is_not_a_skid_steer_command() -> None:
    robot = SkidSteerVehicle.from_catalogue(ROBOT)
    verdict = robot.command(ControlCommand(accel=1.0))  # type: ignore[arg-type]
    assert not verdict.accepted
    assert "ControlCommand" in verdict.reason
    robot.step(1.0)
    assert robot.status().speed == 0.0


def test_teleport_sets_pose_and_straight_motion() -> None:
    ugv = SkidSteerVehicle.from_catalogue(UGV)
    ugv.teleport(Pose(x=5.0, y=-3.0, yaw=1.0), speed=2.5)
    status = ugv.status()
    assert status.pose == Pose(x=5.0, y=-3.0, yaw=1.0)
    assert status.velocity == (2.5, 0.0, 0.0)
    assert status.yaw_rate == 0.0


def test_climbing_a_grade_follows_the_surface() -> None:
    robot = SkidSteerVehicle.from_catalogue(ROBOT)
    grade = RoadSurface(z=0.0, pitch=-math.atan(0.1))
    for _ in drive(robot, SideEffortCommand(throttle=1.0), 5.0, grade):
        pass
    pose = robot.status().pose
    assert pose.pitch == pytest.approx(-math.atan(0.1))
    # Each step climbs 10 % of its level run from the surface's z.
    assert pose.z > 0.0
    assert pose.z == pytest.approx(0.1 * STEP * 1.5 * math.cos(grade.pitch), rel=1e-6)


def test_wheels_carry_their_static_share_and_no_tyre_forces() -> None:
    model = GROUND_VEHICLE_CATALOGUE[UGV]
    ugv = SkidSteerVehicle(model)
    settle(ugv, BodyVelocityCommand(linear=1.0, angular=0.5))
    status = ugv.status()
    wheels = (status.wheels.front_left, status.wheels.rear_right)
    for wheel in wheels:
        assert (wheel.lateral_force, wheel.slip_angle, wheel.cornering_stiffness) == (0, 0, 0)
        assert wheel.vertical_load == pytest.approx(model.mass * 9.80665 / 4)
    assert (status.front_steer, status.rear_steer) == (0.0, 0.0)


def test_same_commands_give_the_same_trajectory_bit_for_bit() -> None:
    commands = [
        SideEffortCommand(throttle=0.7, skid_steering=0.2),
        BodyVelocityCommand(linear=-0.5, angular=-1.0),
        SideEffortCommand(throttle=0.3, brake=0.4),
    ]

    def run() -> list[Pose]:
        robot = SkidSteerVehicle.from_catalogue(ROBOT)
        return [status.pose for command in commands for status in drive(robot, command, 1.3)]

    assert run() == run()


@pytest.mark.parametrize("model", GROUND_VEHICLE_CATALOGUE.values(), ids=GROUND_VEHICLE_CATALOGUE)
def test_every_ground_model_is_geometrically_consistent(model) -> None:
    assert model.front_overhang + model.wheelbase + model.rear_overhang == pytest.approx(
        model.length
    )
    assert model.track_width < model.width
    assert 0.0 < model.turn_efficiency <= 1.0
    assert model.effective_track_width >= model.track_width
    assert model.max_steer_front == 0.0


def test_catalogue_has_a_small_indoor_robot_and_a_six_wheel_ugv() -> None:
    robot, ugv = GROUND_VEHICLE_CATALOGUE[ROBOT], GROUND_VEHICLE_CATALOGUE[UGV]
    assert robot.length < 0.6
    assert robot.max_track_speed == 1.5
    assert ugv.wheel_count == 6
    assert 1.5 < ugv.length < 2.5
    assert ugv.max_track_speed == 5.0
