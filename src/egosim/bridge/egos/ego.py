"""The ego network: EgoVehicleStatus out, CtrlCmd in.

Frames and units of every EgoVehicleStatus field are listed in docs/protocol.md.
"""

from __future__ import annotations

from ...msgs.typed import morai_26_r1
from ...world import EgoLaneState
from ...world.vehicle import ControlCommand, Vehicle, VehicleStatus
from ..context import BridgeContext
from ..protocol.messages import vector3
from ..protocol.releases import CanonicalProfile
from ..protocol.table import Row
from ..protocol.units import deg, heading_deg, mps
from .ground_vehicle import commanded_vehicle

WHEEL_SUFFIXES = (
    ("fl", "front_left"),
    ("fr", "front_right"),
    ("rl", "rear_left"),
    ("rr", "rear_right"),
)


def ego_vehicle_status_fields(
    profile: CanonicalProfile, unique_id: int, status: VehicleStatus, lane: EgoLaneState | None
) -> dict[str, object]:
    """Every morai_msgs/EgoVehicleStatus field of one ego but its header; lane fields are 0
    off the road network."""
    wheels: dict[str, float] = {}
    for suffix, attribute in WHEEL_SUFFIXES:
        wheel = getattr(status.wheels, attribute)
        wheels[f"tire_lateral_force_{suffix}"] = wheel.lateral_force
        wheels[f"side_slip_angle_{suffix}"] = deg(wheel.slip_angle)
        wheels[f"tire_cornering_stiffness_{suffix}"] = wheel.cornering_stiffness
    lateral = lane.lateral_offset if lane is not None else 0.0
    return {
        **ego_motion_fields(profile, unique_id, status),
        "front_steer_angle": deg(status.front_steer),
        "rear_steer_angle": deg(status.rear_steer),
        "lateral_offset": lateral,
        "distance_left_lane_boundary": lane.distance_left if lane is not None else 0.0,
        "distance_right_lane_boundary": lane.distance_right if lane is not None else 0.0,
        "cross_track_error": lane.cross_track_error if lane is not None else 0.0,
        **wheels,
    }


def ego_motion_fields(
    profile: CanonicalProfile, unique_id: int, status: VehicleStatus
) -> dict[str, object]:
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
