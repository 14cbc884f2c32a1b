"""What the page's buttons and keys do, applied on the loop thread as the server hands
them over (ViewControls.apply), with the view's stage run after each step."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from egosim.bridge import BridgeContext, ControlMode
from egosim.view.controls import ViewControls
from egosim.view.hub import FrameHub
from egosim.view.stage import ViewStage
from egosim.world.scenario import load_default_scenario
from egosim.world.vehicle import Gear
from tests import morai_scenarios as morai
from tests.e2e import scenarios

DT = 0.01
KEY_PERIOD_S = 0.1


def controls_of(context: BridgeContext) -> tuple[ViewControls, ViewStage]:
    controls = ViewControls(context, load_default_scenario)
    return controls, ViewStage(context, FrameHub(), controls, "real")


def run(context: BridgeContext, stage: ViewStage, seconds: float) -> None:
    for _ in range(round(seconds / DT)):
        context.world.step(DT)
        stage.after_step()


def drive(context: BridgeContext, controls: ViewControls, seconds: float, **keys: bool) -> None:
    """Hold `keys` for `seconds`, sent every KEY_PERIOD_S as the page does."""
    steps_per_message = round(KEY_PERIOD_S / DT)
    for k in range(round(seconds / DT)):
        if k % steps_per_message == 0:
            assert controls.apply({"op": "keys", "ego": 0, **keys})["ok"]
        context.world.step(DT)


def test_pause_holds_sim_time_and_resume_releases_it(town: BridgeContext) -> None:
    controls, stage = controls_of(town)
    assert controls.apply({"op": "pause"}) == {"ok": True, "op": "pause"}
    run(town, stage, 0.5)
    assert town.world.sim_time == 0.0
    assert controls.apply({"op": "resume"})["ok"]
    run(town, stage, 0.5)
    assert town.world.sim_time == pytest.approx(0.5)


def test_single_step_advances_one_step_and_pauses_again(town: BridgeContext) -> None:
    controls, stage = controls_of(town)
    controls.apply({"op": "pause"})
    assert controls.apply({"op": "step"})["ok"]
    run(town, stage, 0.3)
    assert town.world.sim_time == pytest.approx(DT)
    assert town.world.paused


def test_sync_mode_refuses_the_time_controls(town: BridgeContext) -> None:
    town.sync.start("client", 10)
    controls, _ = controls_of(town)
    for op in ("pause", "resume", "step"):
        reply = controls.apply({"op": op})
        assert not reply["ok"]
        assert "sync mode" in reply["error"]
    assert not town.world.paused


def test_bad_requests_are_answered_not_raised(town: BridgeContext) -> None:
    controls, _ = controls_of(town)
    assert not controls.apply(["pause"])["ok"]
    assert "unknown request" in controls.apply({"op": "explode"})["error"]
    assert not controls.apply({"op": "keys", "ego": 7})["ok"]
    assert not controls.apply({"op": "ctrl_mode", "mode": 9})["ok"]
    assert not controls.apply({"op": "replay", "action": "play"})["ok"]  # no bag loaded


def test_scenarios_load_from_the_data_roots_only(town: BridgeContext, tmp_path: Path) -> None:
    controls, _ = controls_of(town)
    (tmp_path / "sub").mkdir()
    scenarios.write(tmp_path / "sub", "two.yaml", scenarios.TWO_NPCS)
    outside = tmp_path.parent / "outside.yaml"
    outside.write_text(scenarios.TWO_NPCS)
    assert controls.apply({"op": "scenarios"})["scenarios"] == ["sub/two.yaml"]
    reply = controls.apply({"op": "load", "name": "../outside.yaml"})
    assert not reply["ok"]
    assert "outside the data roots" in reply["error"]
    assert controls.apply({"op": "load", "name": "sub/two"}) == {
        "ok": True,
        "op": "load",
        "loaded": "sub/two",
    }
    assert town.world.ego_lane_state(0).lane_id == "R5_E_1"
    assert len(town.world.npcs.unique_ids) == 2


def test_morai_scenarios_are_listed_and_load_but_other_json_is_not_offered(
    town: BridgeContext, tmp_path: Path
) -> None:
    controls, _ = controls_of(town)
    document = morai.scenario(
        "town", vehicles=(morai.npc(morai.on_link("R5_E_1", 0.5), 1, data_id=30100010),)
    )
    morai.write(tmp_path, "morai_scen.json", document)
    (tmp_path / "maps").mkdir()
    (tmp_path / "maps" / "link_set.json").write_text('[{"idx": "L1", "points": []}]')
    (tmp_path / "results.json").write_text('{"cases": []}')
    assert controls.apply({"op": "scenarios"})["scenarios"] == ["morai_scen.json"]
    assert controls.apply({"op": "load", "name": "morai_scen"})["ok"]
    assert town.world.npcs.names == ["2016_Hyundai_Ioniq"]


def test_reload_puts_the_scenario_back(town: BridgeContext) -> None:
    controls, _ = controls_of(town)
    start = town.world.ego_status(0).pose
    town.world.egos[0].vehicle.teleport(type(start)(start.x + 30, start.y, start.z, yaw=start.yaw))
    assert controls.apply({"op": "reload"})["ok"]
    assert town.world.ego_status(0).pose.x == pytest.approx(start.x)


def test_keys_need_keyboard_control_mode(straight: BridgeContext) -> None:
    controls, _ = controls_of(straight)
    reply = controls.apply({"op": "keys", "throttle": True})
    assert not reply["ok"]
    assert "keyboard control mode" in reply["error"]
    assert controls.apply({"op": "ctrl_mode", "mode": 1})["ok"]
    assert straight.ego_session(straight.world.egos[0]).ctrl_mode == ControlMode.KEYBOARD
    assert controls.apply({"op": "keys", "throttle": True})["ok"]
    assert controls.apply({"op": "ctrl_mode", "mode": 3})["ok"]


def heading_progress(context: BridgeContext, start) -> float:
    pose = context.world.ego_status(0).pose
    return (pose.x - start.x) * math.cos(start.yaw) + (pose.y - start.y) * math.sin(start.yaw)


def test_throttle_drives_forward_and_brake_stops(straight: BridgeContext) -> None:
    controls, _ = controls_of(straight)
    controls.apply({"op": "ctrl_mode", "mode": 1})
    start = straight.world.ego_status(0).pose
    drive(straight, controls, 3.0, throttle=True)
    status = straight.world.ego_status(0)
    assert status.speed > 3.0
    assert status.accel_pedal > 0
    assert heading_progress(straight, start) > 3.0
    drive(straight, controls, 6.0, brake=True)  # long enough to stop, then back off
    assert straight.world.egos[0].vehicle.gear is Gear.REVERSE


def test_brake_held_at_rest_reverses(straight: BridgeContext) -> None:
    controls, _ = controls_of(straight)
    controls.apply({"op": "ctrl_mode", "mode": 1})
    start = straight.world.ego_status(0).pose
    drive(straight, controls, 2.0, brake=True)
    assert straight.world.egos[0].vehicle.gear is Gear.REVERSE
    assert heading_progress(straight, start) < -0.5
    drive(straight, controls, 4.0, throttle=True)
    assert straight.world.egos[0].vehicle.gear is Gear.DRIVE


def test_left_key_turns_left_and_the_wheel_returns(straight: BridgeContext) -> None:
    controls, _ = controls_of(straight)
    controls.apply({"op": "ctrl_mode", "mode": 1})
    drive(straight, controls, 2.0, throttle=True)
    yaw = straight.world.ego_status(0).pose.yaw
    drive(straight, controls, 1.5, throttle=True, left=True)
    status = straight.world.ego_status(0)
    assert status.front_steer > 0.05
    assert status.pose.yaw > yaw + 0.05  # counter-clockwise: to the left
    drive(straight, controls, 1.5, throttle=True)
    assert abs(straight.world.ego_status(0).front_steer) < 0.01


def test_a_silent_page_brakes_the_ego_to_a_stop(straight: BridgeContext) -> None:
    controls, stage = controls_of(straight)
    controls.apply({"op": "ctrl_mode", "mode": 1})
    drive(straight, controls, 3.0, throttle=True)
    run(straight, stage, 8.0)  # no more key messages: the page was closed
    status = straight.world.ego_status(0)
    assert status.speed < 0.05
    assert status.brake_pedal == 1.0


def test_leaving_keyboard_mode_releases_the_keyboard_command(straight: BridgeContext) -> None:
    """The page's switch keyboard -> external goes through the ego's session: no throttle is
    kept, the ego brakes until a /ctrl_cmd comes."""
    controls, stage = controls_of(straight)
    controls.apply({"op": "ctrl_mode", "mode": 1})
    drive(straight, controls, 1.5, throttle=True)
    moving = straight.world.ego_status(0)
    assert moving.accel_pedal > 0 and moving.speed > 1.0
    assert controls.apply({"op": "ctrl_mode", "mode": 3})["ok"]
    run(straight, stage, 3.0)  # no /ctrl_cmd
    status = straight.world.ego_status(0)
    assert (status.accel_pedal, status.brake_pedal) == (0.0, 1.0)
    assert status.speed < moving.speed


def test_prepared_loads_read_their_file_before_the_loop_applies_them(
    town: BridgeContext, tmp_path: Path
) -> None:
    controls, _ = controls_of(town)
    path = scenarios.write(tmp_path, "two.yaml", scenarios.TWO_NPCS)
    prepared = controls.prepare({"op": "load", "name": "two"})
    path.unlink()  # the loop never touches the file
    assert controls.apply(prepared)["ok"]
    assert len(town.world.npcs.unique_ids) == 2
    refused = controls.prepare({"op": "load", "name": "missing"})
    assert "not loaded" in controls.apply(refused)["error"]
