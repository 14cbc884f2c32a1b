"""Commands hold until the next one, but only while their input drives: a change of
control mode drops the command in force, so the ego brakes until its new input speaks."""

from __future__ import annotations

import pytest

from egosim.bridge import HANDLERS, ControlMode, simulation_context
from egosim.bridge.context import BridgeContext
from egosim.bridge.egos.events import OPTION_CTRL_MODE
from egosim.bridge.scene.scenarios import apply_network_settings
from egosim.world import World
from egosim.world.map import build_builtin_map
from egosim.world.scenario import parse_scenario


def steps(context: BridgeContext, seconds: float) -> None:
    for _ in range(round(seconds / context.world.physics_step_s)):
        context.world.step()


def set_ctrl_mode(context: BridgeContext, mode: ControlMode) -> None:
    profile = context.profile
    event = profile.message("morai_msgs/EventInfo").new(
        option=OPTION_CTRL_MODE, ctrl_mode=int(mode), gear=-1
    )
    request = profile.message("morai_msgs/MoraiEventCmdSrvRequest").new(request=event)
    HANDLERS.services["event_cmd"].handle(context, context.row("event_cmd"), request)


def drive(context: BridgeContext, message: object) -> None:
    HANDLERS.subscribers["ctrl_cmd"].handle(context, context.row("ctrl_cmd"), message)


def test_one_command_holds_and_a_mode_change_releases_it() -> None:
    context = simulation_context(World(build_builtin_map("straight")))
    throttle = context.profile.message("morai_msgs/CtrlCmd").new(longlCmdType=1, accel=0.5)
    drive(context, throttle)
    steps(context, 5.0)
    status = context.world.ego_status()
    assert (status.accel_pedal, status.brake_pedal) == (0.5, 0.0)
    assert status.speed > 5.0

    set_ctrl_mode(context, ControlMode.KEYBOARD)
    steps(context, 0.01)
    assert context.world.ego_status().brake_pedal == 1.0
    set_ctrl_mode(context, ControlMode.EXTERNAL)
    steps(context, 10.0)
    status = context.world.ego_status()
    assert status.brake_pedal == 1.0
    assert status.speed == pytest.approx(0.0)

    drive(context, throttle)
    steps(context, 0.5)
    assert context.world.ego_status().accel_pedal == 0.5


def test_a_scenario_network_section_sets_the_dead_man_timeout_live() -> None:
    context = simulation_context(World(build_builtin_map("straight")))
    assert context.world.egos[0].vehicle.command_timeout is None
    text = "map: straight\nnetwork:\n  command_timeout_s: 0.5\n"
    apply_network_settings(context, parse_scenario(text, "live.yaml"))
    assert context.world.command_timeout_s == 0.5
    assert context.world.egos[0].vehicle.command_timeout == 0.5
    throttle = context.profile.message("morai_msgs/CtrlCmd").new(longlCmdType=1, accel=0.5)
    drive(context, throttle)
    steps(context, 0.6)
    assert context.world.ego_status().brake_pedal == 1.0


def test_an_egos_run_time_state_changes_only_through_its_session() -> None:
    context = simulation_context(World(build_builtin_map("straight")))
    session = context.ego_session(context.world.egos[0])
    with pytest.raises(AttributeError):
        session.ctrl_mode = ControlMode.AUTO  # type: ignore[misc]
    with pytest.raises(AttributeError):
        session.lamps.turn_signal = 1  # type: ignore[misc]
    assert session.ctrl_mode is ControlMode.EXTERNAL
    assert context.ego_session(context.world.egos[0]) is session

    drive(context, context.profile.message("morai_msgs/CtrlCmd").new(longlCmdType=1, accel=0.5))
    session.set_ctrl_mode(ControlMode.AUTO, by="the test")
    steps(context, 0.01)
    assert context.world.ego_status().accel_pedal == 0.0  # the CtrlCmd was let go of
