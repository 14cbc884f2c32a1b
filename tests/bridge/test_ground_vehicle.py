"""GVDirectCmd, GVStateCmd and Twist drive a skid-steer ego; the wrong kind is ignored."""

from __future__ import annotations

import logging
import math

import pytest

from egosim.bridge import HANDLERS, ControlMode, simulation_context
from egosim.bridge.context import BridgeContext
from egosim.bridge.scene.specs import serve_vehicle_spec
from egosim.msgs import get_profile
from egosim.world import World
from egosim.world.map import build_builtin_map
from egosim.world.scenario import parse_scenario

PROFILE = get_profile("26.r1")
STRAIGHT = build_builtin_map("straight")


def context_with(model: str) -> BridgeContext:
    text = f"map: straight\nego:\n  model: {model}\n  start: {{lane: R1_E_1, s: 10.0}}\n"
    return simulation_context(World(STRAIGHT, parse_scenario(text)))


def direct(**fields: object) -> object:
    return PROFILE.message("morai_msgs/GVDirectCmd").new(**fields)


def state(**fields: object) -> object:
    return PROFILE.message("morai_msgs/GVStateCmd").new(**fields)


def twist(linear_x: float, angular_z: float) -> object:
    vector = PROFILE.message("geometry_msgs/Vector3").new
    return PROFILE.message("geometry_msgs/Twist").new(
        linear=vector(x=linear_x, y=0.0, z=0.0), angular=vector(x=0.0, y=0.0, z=angular_z)
    )


def run(context: BridgeContext, row_key: str, message, seconds: float = 3.0) -> None:
    """Deliver `message` on row `row_key` before every step, as a 100 Hz stream would."""
    handle, row = HANDLERS.subscribers[row_key].handle, context.row(row_key)
    for _ in range(round(seconds / context.world.physics_step_s)):
        handle(context, row, message)
        context.world.step()


def test_direct_throttle_and_skid_steering_move_and_turn_the_robot_left() -> None:
    context = context_with("WeBOT_Indoor_Robot")
    run(context, "gv_direct_cmd", direct(steerType=0, throttle=0.5, skidSteering=0.2))
    status = context.world.ego_status()
    left, right = 0.5 - 0.2, 0.5 + 0.2
    assert status.velocity[0] == pytest.approx(1.5 * (left + right) / 2, abs=1e-3)
    assert status.yaw_rate > 0.0
    assert status.accel_pedal == pytest.approx(0.5)


def test_direct_brake_is_read() -> None:
    context = context_with("WeBOT_Indoor_Robot")
    run(context, "gv_direct_cmd", direct(steerType=0, throttle=1.0, brake=1.0))
    status = context.world.ego_status()
    assert status.speed == 0.0
    assert status.brake_pedal == 1.0


def test_state_command_targets_are_metres_and_radians_per_second() -> None:
    context = context_with("UGV_6W_Skid_Steer")
    message = state(latCtrlType=0, targetLongitudinalVelocity=2.0, targetAngularVelocity=-0.3)
    run(context, "gv_state_cmd", message, seconds=6.0)
    status = context.world.ego_status()
    assert status.velocity[0] == pytest.approx(2.0, abs=1e-3)
    assert status.yaw_rate == pytest.approx(-0.3, abs=1e-3)


def test_webot_twist_reads_linear_x_and_angular_z() -> None:
    context = context_with("WeBOT_Indoor_Robot")
    run(context, "webot_cmd", twist(0.8, 0.5))
    status = context.world.ego_status()
    assert status.velocity[0] == pytest.approx(0.8, abs=1e-3)
    assert status.yaw_rate == pytest.approx(0.5, abs=1e-3)


def test_ground_commands_to_a_car_are_ignored_with_one_warning(caplog) -> None:
    context = context_with("2016_Kia_Niro(HEV)")
    with caplog.at_level(logging.WARNING):
        run(context, "gv_direct_cmd", direct(steerType=0, throttle=1.0), seconds=1.0)
    assert context.world.ego_status().speed == 0.0
    warnings = [r for r in caplog.records if "gv_direct_cmd ignored" in r.getMessage()]
    assert len(warnings) == 1
    assert "2016_Kia_Niro(HEV)" in warnings[0].getMessage()


def test_ctrl_cmd_to_a_skid_steer_is_ignored_with_one_warning(caplog) -> None:
    context = context_with("WeBOT_Indoor_Robot")
    ctrl = PROFILE.message("morai_msgs/CtrlCmd").new(longlCmdType=1, accel=1.0)
    with caplog.at_level(logging.WARNING):
        run(context, "ctrl_cmd", ctrl, seconds=1.0)
    assert context.world.ego_status().speed == 0.0
    assert sum("ctrl_cmd ignored" in r.getMessage() for r in caplog.records) == 1


def test_unsupported_steering_codes_are_ignored_with_a_warning(caplog) -> None:
    context = context_with("WeBOT_Indoor_Robot")
    with caplog.at_level(logging.WARNING):
        run(context, "gv_direct_cmd", direct(steerType=1, throttle=1.0), seconds=0.5)
        run(context, "gv_state_cmd", state(latCtrlType=1, targetLongitudinalVelocity=1.0), 0.5)
    assert context.world.ego_status().speed == 0.0
    messages = [r.getMessage() for r in caplog.records]
    assert sum("steerType 1 is not supported" in m for m in messages) == 1
    assert sum("latCtrlType 1 is not supported" in m for m in messages) == 1


def test_non_finite_targets_are_rejected_once_and_the_robot_keeps_its_command(caplog) -> None:
    context = context_with("WeBOT_Indoor_Robot")
    run(context, "webot_cmd", twist(1.0, 0.0), seconds=2.0)
    with caplog.at_level(logging.WARNING):
        run(context, "webot_cmd", twist(math.nan, 0.0), seconds=0.3)
    assert context.world.ego_status().velocity[0] == pytest.approx(1.0, abs=1e-3)
    assert sum("/commands/vel rejected" in r.getMessage() for r in caplog.records) == 1


def test_ground_commands_wait_for_external_control_mode() -> None:
    context = context_with("WeBOT_Indoor_Robot")
    context.ego_session(context.world.egos[0]).set_ctrl_mode(ControlMode.KEYBOARD, by="the test")
    run(context, "webot_cmd", twist(1.0, 0.0), seconds=1.0)
    assert context.world.ego_status().speed == 0.0


def test_vehicle_spec_of_a_skid_steer_ego_has_its_size_and_no_steering() -> None:
    context = context_with("UGV_6W_Skid_Steer")
    request = PROFILE.message("morai_msgs/MoraiVehicleSpecSrvRequest").new(
        request=PROFILE.message("morai_msgs/VehicleSpecIndex").new(
            unique_id=context.world.egos[0].unique_id
        )
    )
    spec = serve_vehicle_spec(context, context.row("vehicle_spec"), request).response
    assert (spec.size.x, spec.size.y, spec.size.z) == pytest.approx((2.0, 1.4, 1.0))
    assert spec.wheel_base == pytest.approx(1.5)
    assert spec.max_steering == 0.0
    assert spec.overhang + spec.wheel_base + spec.rear_overhang == pytest.approx(2.0)
