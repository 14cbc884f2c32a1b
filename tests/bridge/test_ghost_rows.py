"""Ghost, NPC ghost and multi-ego rows: protocol units and codes in, world state out.

The handlers are driven with decoded messages of the contract's types (no ROS here);
the end-to-end tests check the same rows over the wire.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from egosim.bridge import ControlMode, simulation_context
from egosim.bridge.context import (
    BridgeContext,
)
from egosim.bridge.control_modes import drive_autopilots
from egosim.bridge.egos.ghost import on_ghost_ctrl_cmd, on_npc_ghost
from egosim.bridge.egos.multi_ego import on_multi_ego_setting
from egosim.bridge.scene.specs import vehicle_model_of
from egosim.msgs import get_profile
from egosim.world import World
from egosim.world.map import build_builtin_map
from egosim.world.traffic.ghosts import TurnSignal
from egosim.world.vehicle import Gear

PROFILE = get_profile("26.r1")
MODEL = "2016_Kia_Niro(HEV)"


def _context() -> BridgeContext:
    return simulation_context(World(build_builtin_map("straight")))


def _vector(x: float = 0.0, y: float = 0.0, z: float = 0.0):
    return PROFILE.message("geometry_msgs/Vector3").new(x=x, y=y, z=z)


def _npc_ghost_cmd(*infos: dict):
    info_type = PROFILE.message("morai_msgs/NpcGhostInfo")
    npc_list = [
        info_type.new(
            unique_id=info["unique_id"],
            name=info.get("name", MODEL),
            position=_vector(*info["position"]),
            rpy=_vector(0.0, 0.0, info.get("yaw_deg", 0.0)),
            steering_angle=info.get("steering_angle", 0.0),
            vehicle_speed=info.get("vehicle_speed", 0.0),
            turn_signal=info.get("turn_signal", 0),
            brake_light=info.get("brake_light", False),
        )
        for info in infos
    ]
    return PROFILE.message("morai_msgs/NpcGhostCmd").new(
        header=PROFILE.message("std_msgs/Header").new(), npc_list=npc_list
    )


def _multi_ego(count: int, camera: int = 0, **arrays: list):
    fields = {
        "ego_index": [],
        "global_position_x": [],
        "global_position_y": [],
        "global_position_z": [],
        "global_roll": [],
        "global_pitch": [],
        "global_yaw": [],
        "velocity": [],
        "gear": [],
        "ctrl_mode": [],
        "steering_angle": [],
        "vehicle_speed": [],
        "turn_signal": [],
        "brake_light": [],
    }
    fields.update(arrays)
    return PROFILE.message("morai_msgs/MultiEgoSetting").new(
        number_of_ego_vehicle=count, camera_index=camera, **fields
    )


def test_ghost_message_angles_are_degrees_and_speed_km_per_hour() -> None:
    context = _context()
    message = PROFILE.message("morai_msgs/GhostMessage").new(
        position=_vector(50.0, -1.75, 0.5),
        rotation=_vector(1.0, -2.0, 90.0),
        velocity=72.0,
        steering_angle=-3.0,
    )
    on_ghost_ctrl_cmd(context, context.row("ghost_ctrl_cmd"), message)
    status = context.world.ego_status()
    assert (status.pose.x, status.pose.y, status.pose.z) == (50.0, -1.75, 0.5)
    assert (status.pose.roll, status.pose.pitch, status.pose.yaw) == pytest.approx(
        (math.radians(1.0), math.radians(-2.0), math.pi / 2)
    )
    assert status.velocity[0] == pytest.approx(20.0)
    assert status.front_steer == pytest.approx(math.radians(-3.0))


@pytest.mark.parametrize("velocity", [math.nan, -10.0])
def test_a_bad_ghost_message_leaves_the_ego_where_it_is(velocity: float) -> None:
    context = _context()
    before = context.world.ego_status().pose
    message = PROFILE.message("morai_msgs/GhostMessage").new(
        position=_vector(50.0, 0.0, 0.0), rotation=_vector(), velocity=velocity
    )
    on_ghost_ctrl_cmd(context, context.row("ghost_ctrl_cmd"), message)
    assert context.world.ego_status().pose == before


def test_ghost_message_is_ignored_unless_the_ego_is_external() -> None:
    context = _context()
    context.ego_session(context.world.egos[0]).set_ctrl_mode(ControlMode.KEYBOARD, by="the test")
    before = context.world.ego_status().pose
    message = PROFILE.message("morai_msgs/GhostMessage").new(
        position=_vector(50.0, 0.0, 0.0), rotation=_vector()
    )
    on_ghost_ctrl_cmd(context, context.row("ghost_ctrl_cmd"), message)
    assert context.world.ego_status().pose == before


def test_npc_ghost_info_units_codes_and_refusals() -> None:
    context = _context()
    world = context.world
    ego_id = world.egos[0].unique_id
    on_npc_ghost(
        context,
        context.row("npc_ghost"),
        _npc_ghost_cmd(
            {
                "unique_id": 40,
                "position": (30.0, -5.25, 0.0),
                "yaw_deg": 180.0,
                "vehicle_speed": 18.0,
                "steering_angle": 5.0,
                "turn_signal": 3,
                "brake_light": True,
            },
            {"unique_id": 41, "position": (60.0, -5.25, 0.0), "name": "No_Such_Car"},
            {"unique_id": 42, "position": (90.0, -5.25, 0.0), "turn_signal": 7},
            {"unique_id": 43, "position": (math.inf, -5.25, 0.0)},
            {"unique_id": ego_id, "position": (120.0, -5.25, 0.0)},
        ),
    )
    assert world.npc_ghosts.unique_ids == [40]
    ghost = world.npc_ghosts.get(40)
    assert ghost.position == (30.0, -5.25, 0.0)
    assert ghost.heading == pytest.approx(math.pi)
    assert ghost.speed == pytest.approx(5.0)
    assert ghost.front_steer == pytest.approx(math.radians(5.0))
    assert ghost.turn_signal == TurnSignal.HAZARD
    assert ghost.brake_light is True


def test_multi_ego_setting_adds_and_configures_egos() -> None:
    context = _context()
    world = context.world
    on_multi_ego_setting(
        context,
        context.row("multi_ego_setting"),
        _multi_ego(
            3,
            camera=2,
            ego_index=[2, 1],
            global_position_x=[200.0, 100.0],
            global_position_y=[-5.25, -1.75],
            global_yaw=[180.0, 0.0],
            velocity=[36.0, 0.0],
            gear=[2, 4],
            ctrl_mode=[16, 1],
            turn_signal=[3, 1],
        ),
    )
    assert len(world.egos) == 3
    assert context.session.camera_index == 2
    second, third = world.egos[1], world.egos[2]
    assert (third.vehicle.status().pose.x, third.vehicle.status().pose.yaw) == pytest.approx(
        (200.0, math.pi)
    )
    assert third.vehicle.status().velocity[0] == pytest.approx(10.0)
    assert third.vehicle.gear is Gear.REVERSE
    assert second.vehicle.gear is Gear.DRIVE
    assert context.ego_session(third).ctrl_mode == ControlMode.AUTO
    assert context.ego_session(second).ctrl_mode == ControlMode.KEYBOARD
    lamps = context.ego_session(third).lamps
    assert (lamps.turn_signal, lamps.emergency) == (0, 1)
    lamps = context.ego_session(second).lamps
    assert (lamps.turn_signal, lamps.emergency) == (1, 0)

    drive_autopilots(context)
    assert list(context.session.egos.autopilots) == [third.unique_id]
    on_multi_ego_setting(context, context.row("multi_ego_setting"), _multi_ego(1))
    drive_autopilots(context)
    assert len(world.egos) == 1
    assert context.session.egos.autopilots == {}


@pytest.mark.parametrize(
    "message",
    [
        _multi_ego(0),
        _multi_ego(2, camera=2, ego_index=[1], global_position_x=[1.0], global_position_y=[1.0]),
        _multi_ego(2),  # a new ego without a position
        _multi_ego(2, ego_index=[1], global_position_x=[1.0], global_position_y=[]),
        _multi_ego(2, ego_index=[1, 1], global_position_x=[1.0, 2.0], global_position_y=[1, 2]),
        _multi_ego(2, ego_index=[1], global_position_x=[1.0], global_position_y=[1.0], gear=[9]),
        _multi_ego(
            2, ego_index=[1], global_position_x=[1.0], global_position_y=[1.0], ctrl_mode=[5]
        ),
        _multi_ego(
            2, ego_index=[1], global_position_x=[np.nan], global_position_y=[1.0], ctrl_mode=[3]
        ),
    ],
)
def test_a_bad_multi_ego_setting_changes_nothing(message) -> None:
    context = _context()
    on_multi_ego_setting(context, context.row("multi_ego_setting"), message)
    assert len(context.world.egos) == 1
    assert context.session.camera_index == 0
    assert context.ego_session(context.world.egos[0]).ctrl_mode == ControlMode.EXTERNAL


def test_a_ghost_npc_has_the_vehicle_spec_of_its_model() -> None:
    context = _context()
    on_npc_ghost(
        context,
        context.row("npc_ghost"),
        _npc_ghost_cmd({"unique_id": 500, "position": (20.0, -1.75, 0.0)}),
    )
    model = vehicle_model_of(context.world, 500)
    assert model is not None and model.name == MODEL
    assert vehicle_model_of(context.world, 501) is None
