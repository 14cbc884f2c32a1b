"""Protocol units at the edge: degrees and km/h where the document asks for them."""

from __future__ import annotations

import math

import pytest

from egosim.bridge import simulation_context
from egosim.bridge.egos.ego import control_command, ego_vehicle_status_fields, on_ctrl_cmd
from egosim.bridge.protocol.messages import header
from egosim.bridge.protocol.units import heading_deg
from egosim.bridge.scene.specs import map_spec, vehicle_spec
from egosim.msgs import get_profile
from egosim.world import World
from egosim.world.map import build_builtin_map
from egosim.world.map.georef import GeoReference
from egosim.world.vehicle import LongitudinalMode, Pose, vehicle_model

PROFILE = get_profile("26.r1")


def test_ego_status_reports_angles_in_degrees_and_lane_quantities() -> None:
    world = World(build_builtin_map("straight"))
    pose = Pose(x=100.0, y=-1.0, yaw=0.0)
    world.egos[0].vehicle.teleport(pose, speed=10.0, front_steer=0.05)
    lane = world.ego_lane_state()
    message = PROFILE.message("morai_msgs/EgoVehicleStatus").new(
        header=header(PROFILE, 1_000_000_000, "map"),
        **ego_vehicle_status_fields(PROFILE, -1, world.ego_status(), lane),
    )
    assert message.heading == pytest.approx(0.0)
    assert message.front_steer_angle == pytest.approx(math.degrees(0.05))
    assert message.velocity.x == pytest.approx(10.0)
    assert message.position.x == pytest.approx(100.0)
    assert message.lateral_offset == pytest.approx(lane.lateral_offset)
    assert message.cross_track_error == pytest.approx(-lane.lateral_offset)
    assert message.distance_left_lane_boundary + message.distance_right_lane_boundary == (
        pytest.approx(3.5)
    )
    data = PROFILE.message("morai_msgs/EgoVehicleStatus").serialize(message)
    assert PROFILE.message("morai_msgs/EgoVehicleStatus").deserialize(data).heading == 0.0


@pytest.mark.parametrize(("yaw", "heading"), [(0.0, 0.0), (math.pi, 180.0), (-math.pi / 2, -90.0)])
def test_heading_is_enu_degrees_wrapped(yaw: float, heading: float) -> None:
    assert heading_deg(yaw) == pytest.approx(heading)
    assert heading_deg(yaw + 4 * math.pi) == pytest.approx(heading)


def test_ctrl_cmd_velocity_is_km_per_hour() -> None:
    ctrl = PROFILE.message("morai_msgs/CtrlCmd").new(
        longlCmdType=2, velocity=36.0, front_steer=0.1, rear_steer=-0.02
    )
    command = control_command(ctrl)
    assert command.mode == LongitudinalMode.VELOCITY
    assert command.velocity == pytest.approx(10.0)
    assert (command.front_steer, command.rear_steer) == (pytest.approx(0.1), -0.02)


def test_vehicle_spec_of_the_default_ego() -> None:
    model = vehicle_model("2016_Kia_Niro(HEV)")
    spec = vehicle_spec(PROFILE, model)
    assert (spec.size.x, spec.size.y, spec.size.z) == pytest.approx((4.355, 1.805, 1.535))
    assert spec.wheel_base == pytest.approx(2.7)
    assert spec.max_steering == pytest.approx(math.degrees(model.max_steer_front))
    assert spec.overhang == pytest.approx(0.87)
    assert spec.rear_overhang == pytest.approx(0.785)


def test_vehicle_spec_of_nothing_is_all_zero() -> None:
    spec = vehicle_spec(PROFILE, None)
    assert (spec.size.x, spec.wheel_base, spec.max_steering) == (0.0, 0.0, 0.0)


def test_map_spec_of_the_town_is_utm_52n() -> None:
    georef = build_builtin_map("town").georef
    spec = map_spec(PROFILE, georef)
    assert spec.plane_coordinate_system == 0
    assert spec.utm_num == 52
    assert spec.central_meridian == pytest.approx(129.0)
    assert spec.scale_factor == pytest.approx(0.9996)
    assert spec.false_easting == pytest.approx(500000.0)
    assert spec.false_northing == 0.0
    assert (spec.utm_offset.x, spec.utm_offset.y) == (georef.origin_east, georef.origin_north)
    assert spec.ellipse == "WGS84"


def test_map_spec_of_a_map_in_a_transverse_mercator_grid_is_tm() -> None:
    # Korea 2000 / Central Belt 2010: TM, latitude of origin 38, central meridian 127.
    georef = GeoReference.from_projection("EPSG:5186", (200_000.0, 500_000.0, 0.0))
    spec = map_spec(PROFILE, georef)
    assert spec.plane_coordinate_system == 1
    assert spec.central_latitude == pytest.approx(38.0)
    assert spec.central_meridian == pytest.approx(127.0)
    assert spec.scale_factor == pytest.approx(1.0)
    assert (spec.false_easting, spec.false_northing) == pytest.approx((200_000.0, 600_000.0))


def test_a_stream_of_rejected_commands_is_logged_once_and_the_valid_one_stays(caplog) -> None:
    world = World(build_builtin_map("straight"))
    context = simulation_context(world)
    ctrl = PROFILE.message("morai_msgs/CtrlCmd")
    on_ctrl_cmd(
        context,
        context.row("ctrl_cmd"),
        ctrl.new(longlCmdType=2, velocity=36.0),
    )
    for _ in range(50):
        on_ctrl_cmd(
            context,
            context.row("ctrl_cmd"),
            ctrl.new(longlCmdType=2, velocity=math.nan),
        )
    rejections = [r for r in caplog.records if "rejected" in r.getMessage()]
    assert len(rejections) == 1
    for _ in range(40):  # within the 0.5 s command timeout
        world.step(0.01)
    assert world.ego_status().accel_pedal > 0.0  # still driving to the last valid 36 km/h
