"""The ego network: EgoVehicleStatus out, CtrlCmd in.

Frames and units of every EgoVehicleStatus field are listed in docs/protocol.md.
"""

from __future__ import annotations

from typing import TypedDict

from ...msgs.typed import morai_26_r1, standard
from ...world import EgoLaneState
from ...world.vehicle import ControlCommand, Vehicle, VehicleStatus
from ..context import BridgeContext
from ..protocol.messages import vector3
from ..protocol.releases import CanonicalProfile
from ..protocol.table import Row
from ..protocol.units import deg, heading_deg, mps
from .ground_vehicle import commanded_vehicle


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


def ego_vehicle_status_fields(
    profile: CanonicalProfile, unique_id: int, status: VehicleStatus, lane: EgoLaneState | None
) -> EgoVehicleStatusFields:
    """Every morai_msgs/EgoVehicleStatus field of one ego but its header, in protocol
    units; lane fields are 0 off the road network."""
    wheels = status.wheels
    fl, fr, rl, rr = wheels.front_left, wheels.front_right, wheels.rear_left, wheels.rear_right
    return {
        **ego_motion_fields(profile, unique_id, status),
        "front_steer_angle": deg(status.front_steer),
        "rear_steer_angle": deg(status.rear_steer),
        "lateral_offset": lane.lateral_offset if lane is not None else 0.0,
        "distance_left_lane_boundary": lane.distance_left if lane is not None else 0.0,
        "distance_right_lane_boundary": lane.distance_right if lane is not None else 0.0,
        "cross_track_error": lane.cross_track_error if lane is not None else 0.0,
        "tire_lateral_force_fl": fl.lateral_force,
        "tire_lateral_force_fr": fr.lateral_force,
        "tire_lateral_force_rl": rl.lateral_force,
        "tire_lateral_force_rr": rr.lateral_force,
        "side_slip_angle_fl": deg(fl.slip_angle),
        "side_slip_angle_fr": deg(fr.slip_angle),
        "side_slip_angle_rl": deg(rl.slip_angle),
        "side_slip_angle_rr": deg(rr.slip_angle),
        "tire_cornering_stiffness_fl": fl.cornering_stiffness,
        "tire_cornering_stiffness_fr": fr.cornering_stiffness,
        "tire_cornering_stiffness_rl": rl.cornering_stiffness,
        "tire_cornering_stiffness_rr": rr.cornering_stiffness,
    }


def ego_motion_fields(
    profile: CanonicalProfile, unique_id: int, status: VehicleStatus
) -> EgoMotionFields:
    """The fields EgoVehicleStatus and EgoVehicleStatusExtended share but the header, in
    protocol units."""
    pose = status.pose
    return {
        "unique_id": unique_id,
        "acceleration": vector3(profile, status.acceleration),
        "position": vector3(profile, (pose.x, pose.y, pose.z)),
        "velocity": vector3(profile, status.velocity),
        "heading": heading_deg(pose.yaw),
        "accel": status.accel_pedal,
        "brake": status.brake_pedal,
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


def publish_ego_status(context: BridgeContext, row: Row) -> morai_26_r1.EgoVehicleStatus:
    """/Ego_topic: the ego MultiEgoSetting's camera_index selects (the main ego by default)."""
    world = context.world
    camera_index = context.session.camera_index
    index = camera_index if camera_index < len(world.egos) else 0
    return ego_status_of(context, index, stamped=False)


def ego_status_of(
    context: BridgeContext, index: int, *, stamped: bool = True
) -> morai_26_r1.EgoVehicleStatus:
    """EgoVehicleStatus of the ego at `index` of the world's egos; unstamped for the row's
    outlet to stamp (BridgeContext.header)."""
    world = context.world
    fields = ego_vehicle_status_fields(
        context.profile,
        world.egos[index].unique_id,
        world.ego_status(index),
        world.ego_lane_state(index),
    )
    message_type = context.profile.message("morai_msgs/EgoVehicleStatus")
    return message_type.new(header=context.header(stamped=stamped), **fields)


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
