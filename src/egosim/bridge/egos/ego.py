"""The ego network: EgoVehicleStatus out, CtrlCmd in.

Frames and units of every EgoVehicleStatus field are listed in docs/protocol.md.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, TypedDict

from ...world import EgoLaneState
from ...world.vehicle import ControlCommand, Vehicle, VehicleStatus
from ..context import MAP_FRAME, BridgeContext
from ..protocol.messages import vector3
from ..protocol.table import Row
from ..protocol.units import deg, heading_deg, mps
from .ground_vehicle import commanded_vehicle

if TYPE_CHECKING:
    from ...msgs.typed import morai_26_r1, standard
    from ..protocol.releases import CanonicalProfile


class EgoMotionFields(TypedDict):
    """The fields EgoVehicleStatus and EgoVehicleStatusExtended share but the header."""

    unique_id: int
    acceleration: standard.Vector3
    position: standard.Vector3
    velocity: standard.Vector3
    heading: float
    accel: float
    brake: float


class EgoVehicleStatusFields(EgoMotionFields):
    """Every morai_msgs/EgoVehicleStatus field but its header."""

    front_steer_angle: float
    rear_steer_angle: float
    lateral_offset: float
    distance_left_lane_boundary: float
    distance_right_lane_boundary: float
    cross_track_error: float
    tire_lateral_force_fl: float
    tire_lateral_force_fr: float
    tire_lateral_force_rl: float
    tire_lateral_force_rr: float
    side_slip_angle_fl: float
    side_slip_angle_fr: float
    side_slip_angle_rl: float
    side_slip_angle_rr: float
    tire_cornering_stiffness_fl: float
    tire_cornering_stiffness_fr: float
    tire_cornering_stiffness_rl: float
    tire_cornering_stiffness_rr: float


def ego_status_values(
    unique_id: int, status: VehicleStatus, lane: EgoLaneState | None
) -> tuple[float, ...]:
    """Every morai_msgs/EgoVehicleStatus field of one ego after its header, in protocol
    units and in wire order (its flat packer's leaves from unique_id on); lane fields
    are 0 off the road network."""
    pose = status.pose
    wheels = status.wheels
    tyres = (wheels.front_left, wheels.front_right, wheels.rear_left, wheels.rear_right)
    return (
        unique_id,
        *(float(value) for value in status.acceleration),
        *(float(pose.x), float(pose.y), float(pose.z)),
        *(float(value) for value in status.velocity),
        heading_deg(pose.yaw),
        status.accel_pedal,
        status.brake_pedal,
        deg(status.front_steer),
        deg(status.rear_steer),
        lane.lateral_offset if lane is not None else 0.0,
        *(tyre.lateral_force for tyre in tyres),
        *(deg(tyre.slip_angle) for tyre in tyres),
        *(tyre.cornering_stiffness for tyre in tyres),
        lane.distance_left if lane is not None else 0.0,
        lane.distance_right if lane is not None else 0.0,
        lane.cross_track_error if lane is not None else 0.0,
    )


def ego_vehicle_status_fields(
    profile: CanonicalProfile, unique_id: int, status: VehicleStatus, lane: EgoLaneState | None
) -> EgoVehicleStatusFields:
    """Every morai_msgs/EgoVehicleStatus field of one ego but its header, in protocol
    units; lane fields are 0 off the road network."""
    (
        _, *_motion, front_steer, rear_steer, lateral_offset,
        force_fl, force_fr, force_rl, force_rr,
        slip_fl, slip_fr, slip_rl, slip_rr,
        stiffness_fl, stiffness_fr, stiffness_rl, stiffness_rr,
        distance_left, distance_right, cross_track_error,
    ) = ego_status_values(unique_id, status, lane)  # fmt: skip
    return {
        **ego_motion_fields(profile, unique_id, status),
        "front_steer_angle": front_steer,
        "rear_steer_angle": rear_steer,
        "lateral_offset": lateral_offset,
        "distance_left_lane_boundary": distance_left,
        "distance_right_lane_boundary": distance_right,
        "cross_track_error": cross_track_error,
        "tire_lateral_force_fl": force_fl,
        "tire_lateral_force_fr": force_fr,
        "tire_lateral_force_rl": force_rl,
        "tire_lateral_force_rr": force_rr,
        "side_slip_angle_fl": slip_fl,
        "side_slip_angle_fr": slip_fr,
        "side_slip_angle_rl": slip_rl,
        "side_slip_angle_rr": slip_rr,
        "tire_cornering_stiffness_fl": stiffness_fl,
        "tire_cornering_stiffness_fr": stiffness_fr,
        "tire_cornering_stiffness_rl": stiffness_rl,
        "tire_cornering_stiffness_rr": stiffness_rr,
    }


def ego_motion_fields(
    profile: CanonicalProfile, unique_id: int, status: VehicleStatus
) -> EgoMotionFields:
    """The fields EgoVehicleStatus and EgoVehicleStatusExtended share but the header, in
    protocol units."""
    _, *acceleration_position_velocity, heading, accel, brake = ego_status_values(
        unique_id, status, None
    )[:13]
    values = acceleration_position_velocity
    return {
        "unique_id": unique_id,
        "acceleration": vector3(profile, values[0:3]),
        "position": vector3(profile, values[3:6]),
        "velocity": vector3(profile, values[6:9]),
        "heading": heading,
        "accel": accel,
        "brake": brake,
    }


def control_command(ctrl_cmd: morai_26_r1.CtrlCmd) -> ControlCommand:
    """A morai_msgs/CtrlCmd in SI: velocity km/h -> m/s; angles are already rad."""
    return ControlCommand(
        mode=int(ctrl_cmd.longlCmdType),
        accel=float(ctrl_cmd.accel),
        brake=float(ctrl_cmd.brake),
        front_steer=float(ctrl_cmd.front_steer),
        rear_steer=float(ctrl_cmd.rear_steer),
        velocity=mps(float(ctrl_cmd.velocity)),
        acceleration=float(ctrl_cmd.acceleration),
    )


def publish_ego_status(context: BridgeContext, row: Row) -> bytes:
    """/Ego_topic: the ego MultiEgoSetting's camera_index selects (the main ego by default).
    Its bytes, for the outlet to stamp."""
    world = context.world
    camera_index = context.session.camera_index
    index = camera_index if camera_index < len(world.egos) else 0
    values = ego_status_values(
        world.egos[index].unique_id, world.ego_status(index), world.ego_lane_state(index)
    )
    pack = context.profile.message("morai_msgs/EgoVehicleStatus").flat().pack
    return pack(0, 0, 0, MAP_FRAME, *values)  # header: seq and stamp written by the outlet


def ego_status_of(context: BridgeContext, index: int) -> morai_26_r1.EgoVehicleStatus:
    """EgoVehicleStatus of the ego at `index` of the world's egos."""
    world = context.world
    fields = ego_vehicle_status_fields(
        context.profile,
        world.egos[index].unique_id,
        world.ego_status(index),
        world.ego_lane_state(index),
    )
    message_type = context.profile.message("morai_msgs/EgoVehicleStatus")
    return message_type.new(header=context.header(), **fields)


def on_ctrl_cmd(context: BridgeContext, row: Row, ctrl_cmd: morai_26_r1.CtrlCmd) -> None:
    """/ctrl_cmd drives the main ego while its control mode is external (EventInfo 3)
    and it is a road vehicle."""
    drive_with_ctrl_cmd(context, row, 0, ctrl_cmd)


def drive_with_ctrl_cmd(
    context: BridgeContext, row: Row, index: int, ctrl_cmd: morai_26_r1.CtrlCmd
) -> None:
    """Hand a CtrlCmd received on `row` to the ego at `index` if its control mode and kind
    take it."""
    vehicle = commanded_vehicle(context, row, index, Vehicle)
    if vehicle is None:
        return
    verdict = vehicle.command(control_command(ctrl_cmd))
    if not verdict.accepted:
        context.warn_throttled(
            f"{row.name}: {verdict.reason}",
            f"{row.name} rejected (last valid command kept): {verdict.reason}",
        )
