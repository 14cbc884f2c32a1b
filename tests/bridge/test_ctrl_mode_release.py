"""Commands hold until the next one, but only while their input drives: a change of
control mode drops the command in force, so the ego brakes until its new input speaks."""

from __future__ import annotations

import pytest

from egosim.bridge.context import CTRL_MODE_EXTERNAL, CTRL_MODE_KEYBOARD, BridgeContext
from egosim.bridge.ego import on_ctrl_cmd
from egosim.bridge.events import OPTION_CTRL_MODE, serve_event_cmd
from egosim.msgs import get_profile
from egosim.world import World
from egosim.world.map import build_builtin_map

PROFILE = get_profile("26.r1")


def steps(context: BridgeContext, seconds: float) -> None:
    for _ in range(round(seconds / context.world.physics_step_s)):
        context.world.step()


def set_ctrl_mode(context: BridgeContext, mode: int) -> None:
    event = PROFILE.message("morai_msgs/EventInfo").new(
        option=OPTION_CTRL_MODE, ctrl_mode=mode, gear=-1
    )
    request = PROFILE.message("morai_msgs/MoraiEventCmdSrvRequest").new(request=event)
    serve_event_cmd(context, request)


def test_one_command_holds_and_a_mode_change_releases_it() -> None:
    context = BridgeContext(PROFILE, World(build_builtin_map("straight")), lambda: 0.0)
    throttle = PROFILE.message("morai_msgs/CtrlCmd").new(longlCmdType=1, accel=0.5)
    on_ctrl_cmd(context, throttle)
    steps(context, 5.0)
    status = context.world.ego_status()
    assert (status.accel_pedal, status.brake_pedal) == (0.5, 0.0)
    assert status.speed > 5.0

    set_ctrl_mode(context, CTRL_MODE_KEYBOARD)
    steps(context, 0.01)
    assert context.world.ego_status().brake_pedal == 1.0
    set_ctrl_mode(context, CTRL_MODE_EXTERNAL)
    steps(context, 10.0)
    status = context.world.ego_status()
    assert status.brake_pedal == 1.0
    assert status.speed == pytest.approx(0.0)

    on_ctrl_cmd(context, throttle)
    steps(context, 0.5)
    assert context.world.ego_status().accel_pedal == 0.5
