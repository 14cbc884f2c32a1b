"""The replay rows over a drive with a closed-form trajectory: /Morai_SimProc commands,
what the world shows while replaying, MoraiSimProcStatus and ReplayInfo."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import pytest

from egosim.bridge import simulation_context
from egosim.bridge.context import BridgeContext
from egosim.bridge.replay.replay_rows import (
    advance_replay,
    publish_replay_info,
    serve_sim_proc,
)
from egosim.bridge.replay.replayed_scene import world_object
from egosim.bridge.scene.objects import object_status
from egosim.msgs import get_profile
from egosim.replay import ObjectState
from egosim.world import World
from egosim.world.map import build_builtin_map
from egosim.world.scenario import load_default_scenario
from egosim.world.traffic import ObjectType
from tests.bridge.built_rows import built
from tests.replay.drive import (
    DURATION_S,
    MOVING_OBJECTS,
    OMEGA,
    RADIUS_M,
    SPEED_MS,
    ego_heading,
    ego_pedal,
    ego_position,
    record_drive,
)

PROFILE = get_profile("26.r1")
DT = 0.01
PLAY, PAUSE, STOP = 1, 2, 32
LOAD, SET_TARGET, SET_SPEED = 0x0001, 0x0010, 0x1000
TARGET_NPC = 0x0010
RECORDED_NPCS = {o.unique_id: o for o in MOVING_OBJECTS if o.list_name == "npc_list"}
RECORDED_PEDESTRIANS = {o.unique_id for o in MOVING_OBJECTS if o.list_name == "pedestrian_list"}


@pytest.fixture(scope="module")
def bag(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return record_drive(tmp_path_factory.mktemp("data") / "drive.bag")


@pytest.fixture
def context(bag: Path) -> BridgeContext:
    world = World(build_builtin_map("town"), load_default_scenario(), physics_step_s=DT)
    return simulation_context(world, data_roots=(bag.parent,))


def command(context: BridgeContext, **fields: Any) -> bool:
    fields.setdefault("replay_speed", 1)
    handle = PROFILE.message("morai_msgs/MoraiSimProcHandle").new(**fields)
    request = PROFILE.service("morai_msgs/MoraiSimProcSrv").request.new(request=handle)
    return bool(serve_sim_proc(context, context.row("sim_proc"), request).response.result)


def run(context: BridgeContext, seconds: float) -> None:
    """The loop's order: the replay moves, then the world steps."""
    for _ in range(round(seconds / DT)):
        advance_replay(context, DT)
        context.world.step(DT)


def status(context: BridgeContext) -> tuple[int, int, int]:
    message = built(context, "sim_proc_status")
    return message.command_result, message.current_mode, message.current_status


def listed(context: BridgeContext) -> dict[str, dict[int, Any]]:
    message = built(context, "object_status")
    return {
        name: {o.unique_id: o for o in getattr(message, name)}
        for name in ("npc_list", "pedestrian_list", "obstacle_list")
    }


def test_status_before_any_command_is_initial_simulation_running(
    context: BridgeContext,
) -> None:
    assert status(context) == (0x00, 0x01, 0x01)
    latest = built(context, "sim_proc_status").latest_command_time
    assert (latest.sec, latest.nanosec) == (0, 0)
    assert (
        publish_replay_info(
            context,
            context.row("replay_info"),
        )
        is None
    )


@pytest.mark.parametrize("speed", [1, 4])
def test_the_ego_and_objects_follow_the_recording(context: BridgeContext, speed: int) -> None:
    run(context, 0.5)
    assert command(
        context,
        sim_process_status=PLAY,
        replay_option=LOAD | SET_SPEED,
        rosbag_file_name="drive.bag",
        replay_speed=speed,
    )
    assert status(context) == (0x01, 0x10, 0x01)
    run(context, 1.0)
    t = 1.0 * speed
    ego = built(context, "ego_status")
    assert math.dist((ego.position.x, ego.position.y), ego_position(t)[:2]) < 1e-3
    assert math.radians(ego.heading) == pytest.approx(ego_heading(t), abs=1e-4)
    assert ego.velocity.x == pytest.approx(SPEED_MS)
    lists = listed(context)
    assert lists["npc_list"].keys() == {i for i, o in RECORDED_NPCS.items() if t < o.until_s}
    assert lists["pedestrian_list"].keys() == RECORDED_PEDESTRIANS
    assert lists["obstacle_list"] == {}
    for unique_id, shown in lists["npc_list"].items():
        expected = RECORDED_NPCS[unique_id].position(t)
        assert (shown.position.x, shown.position.y) == pytest.approx(expected[:2], abs=1e-9)
    run(context, DURATION_S / speed)
    assert status(context) == (0x01, 0x10, 0x20)


def test_unselected_targets_keep_being_simulated_and_stop_restores_the_agents(
    context: BridgeContext,
) -> None:
    run(context, 0.5)
    simulated = listed(context)
    start = built(context, "ego_status").position
    assert command(
        context,
        sim_process_status=PLAY,
        replay_option=LOAD | SET_TARGET,
        rosbag_file_name="drive.bag",
        replay_target_option=TARGET_NPC,
    )
    run(context, 1.0)
    ego = built(context, "ego_status").position
    assert (ego.x, ego.y) == pytest.approx((start.x, start.y), abs=0.05)  # undriven, in place
    lists = listed(context)
    assert lists["npc_list"].keys() == RECORDED_NPCS.keys()
    assert lists["obstacle_list"] == {}  # obstacles go with the NPCs
    assert lists["pedestrian_list"].keys() == simulated["pedestrian_list"].keys()

    assert command(context, sim_process_status=STOP)
    assert status(context) == (0x01, 0x01, 0x01)
    assert (
        publish_replay_info(
            context,
            context.row("replay_info"),
        )
        is None
    )
    back = listed(context)
    assert back["npc_list"].keys() == simulated["npc_list"].keys()
    assert back["obstacle_list"].keys() == simulated["obstacle_list"].keys()
    for unique_id, npc in back["npc_list"].items():  # they waited where they were
        before = simulated["npc_list"][unique_id]
        assert (npc.position.x, npc.position.y) == (before.position.x, before.position.y)
    run(context, 1.0)
    moved = listed(context)["npc_list"]
    assert any(moved[u].position.x != back["npc_list"][u].position.x for u in moved)


def test_replay_info_reports_recorded_inputs_in_protocol_units(context: BridgeContext) -> None:
    assert command(
        context, sim_process_status=PLAY, replay_option=LOAD, rosbag_file_name="drive.bag"
    )
    run(context, 2.0)
    info = publish_replay_info(context, context.row("replay_info"))
    assert info.ego_acc == pytest.approx(ego_pedal(2.0), abs=1e-4)
    assert info.ego_brake == 0.0
    assert info.ego_steer == pytest.approx(math.degrees(math.atan(2.7 / RADIUS_M)))
    q = info.orientation
    assert 2 * math.atan2(q.z, q.w) == pytest.approx(ego_heading(2.0), abs=1e-4)
    assert info.angular_velocity.z == pytest.approx(OMEGA, rel=1e-6)
    assert info.linear_acceleration.y == pytest.approx(SPEED_MS * OMEGA)
    assert (info.num_of_npcs, info.num_of_pedestrian, info.num_of_obstacle) == (3, 1, 0)
    npcs = {o.unique_id: o for o in info.npc_list}
    for unique_id, npc in RECORDED_NPCS.items():
        # Listed as recorded: heading in deg, velocity in km/h (the drive's own values).
        velocity = npcs[unique_id].velocity
        assert (velocity.x, velocity.y) == pytest.approx(
            (npc.velocity[0] * 3.6, npc.velocity[1] * 3.6)
        )
        assert npcs[unique_id].heading == pytest.approx(npc.heading_deg())
        assert (npcs[unique_id].position.x, npcs[unique_id].position.y) == pytest.approx(
            npc.position(2.0)[:2]
        )


def test_pause_holds_the_recorded_scene(context: BridgeContext) -> None:
    assert command(
        context, sim_process_status=PLAY, replay_option=LOAD, rosbag_file_name="drive.bag"
    )
    run(context, 1.0)
    assert command(context, sim_process_status=PAUSE)
    held = built(context, "ego_status").position
    run(context, 1.0)
    assert status(context) == (0x01, 0x10, 0x10)
    assert built(context, "ego_status").position == held


@pytest.mark.parametrize("name", ["missing.bag", "../drive.bag", "/etc/hostname"])
def test_a_bag_that_cannot_load_fails_with_0x20_and_changes_nothing(
    context: BridgeContext, name: str
) -> None:
    run(context, 0.2)
    before = listed(context)
    assert not command(context, sim_process_status=PLAY, replay_option=LOAD, rosbag_file_name=name)
    assert status(context) == (0x20, 0x01, 0x01)
    latest = built(context, "sim_proc_status").latest_command_time
    assert latest.nanosec == pytest.approx(0.2e9, abs=1e3)
    assert listed(context).keys() == before.keys()
    assert listed(context)["npc_list"].keys() == before["npc_list"].keys()


def test_a_recorded_object_moves_in_the_map_frame_and_reads_back_as_recorded() -> None:
    recorded = ObjectState(
        unique_id=7,
        type=1,
        name="car",
        position=(1.0, 2.0, 0.0),
        heading=math.pi / 2,  # facing north
        velocity=(10.0, 0.0, 0.0),  # m/s forward, in its own frame
        acceleration=(0.0, 1.0, 0.0),  # m/s^2 to its left
        size=(1.8, 4.5, 1.5),  # width, length, height, as ObjectStatus lists them
    )
    shown = world_object(recorded, ObjectType.NPC_VEHICLE)
    assert shown.velocity == pytest.approx((0.0, 10.0, 0.0))
    assert shown.acceleration == pytest.approx((-1.0, 0.0, 0.0))
    assert shown.size == (4.5, 1.8, 1.5)  # the world keeps the length first
    status = object_status(PROFILE, shown)
    assert (status.size.x, status.size.y, status.size.z) == (1.8, 4.5, 1.5)
    assert (status.velocity.x, status.velocity.y) == pytest.approx((36.0, 0.0))
    assert (status.acceleration.x, status.acceleration.y) == pytest.approx((0.0, 1.0))
    assert status.heading == pytest.approx(90.0)
