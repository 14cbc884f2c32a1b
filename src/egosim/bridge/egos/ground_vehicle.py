"""Ground vehicle command inputs: GVDirectCmd, GVStateCmd and WeBOT's geometry_msgs/Twist.

They drive a main ego whose model is a ground vehicle (a skid-steer); sent to a
car they are ignored, as CtrlCmd is when the ego is a skid-steer, with one
warning per row. All their quantities are already SI (m/s, rad/s, -1..1).
Semantics and codes are listed in docs/protocol.md.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, TypeVar

from ...world.vehicle import (
    BodyVelocityCommand,
    SideEffortCommand,
    SkidSteerVehicle,
    Vehicle,
)
from ..context import BridgeContext
from ..protocol.codes import ControlMode
from ..protocol.table import Row

if TYPE_CHECKING:
    from ...msgs.typed import morai_26_r1, standard

VehicleT = TypeVar("VehicleT", Vehicle, SkidSteerVehicle)

# GVDirectCmd.steerType (the protocol document's "Table 1" is missing; these are egosim's).
STEER_TYPE_SKID = 0  # throttle and skidSteering drive the two sides
STEER_TYPE_WHEEL_ANGLES = 1  # steerAngle[] steers the wheels: no ground model has steered wheels

# GVStateCmd.latCtrlType, numbered like steerType.
LAT_CTRL_ANGULAR_VELOCITY = 0  # targetAngularVelocity sets the yaw rate
LAT_CTRL_STEER_ANGLES = 1  # targetSteerAngle[]: as STEER_TYPE_WHEEL_ANGLES, unsupported


def commanded_main_vehicle(
    context: BridgeContext, row: Row, kind: type[VehicleT]
) -> VehicleT | None:
    """The main ego's vehicle when a command of `row` may drive it: the ego's control mode
    is external (EventInfo 3) and its vehicle is of `kind`; None otherwise."""
    return commanded_vehicle(context, row, 0, kind)


def commanded_vehicle(
    context: BridgeContext, row: Row, index: int, kind: type[VehicleT]
) -> VehicleT | None:
    """commanded_main_vehicle for the ego at `index` of the world's egos."""
    ego = context.world.egos[index]
    if context.ego_session(ego).ctrl_mode is not ControlMode.EXTERNAL:
        return None
    if not isinstance(ego.vehicle, kind):
        context.warn_throttled(
            f"{row.name}: kind",
            f"{row.name} ignored: the ego's model {ego.vehicle.model.name} does not take it "
            f"(ground vehicle models take webot_cmd, gv_direct_cmd, gv_state_cmd; "
            f"road vehicles take ctrl_cmd)",
        )
        return None
    return ego.vehicle


def _drive(
    context: BridgeContext, row: Row, command: SideEffortCommand | BodyVelocityCommand
) -> None:
    vehicle = commanded_main_vehicle(context, row, SkidSteerVehicle)
    if vehicle is None:
        return
    verdict = vehicle.command(command)
    if not verdict.accepted:
        context.warn_throttled(
            f"{row.name}: {verdict.reason}",
            f"{row.name} rejected (last valid command kept): {verdict.reason}",
        )


def on_gv_direct_cmd(context: BridgeContext, row: Row, message: morai_26_r1.GVDirectCmd) -> None:
    """/gv_direct_cmd: throttle, skid steering and brake of the two sides (steerType 0)."""
    if message.steerType != STEER_TYPE_SKID:
        context.warn_throttled(
            f"{row.name}: steerType {message.steerType}",
            f"{row.name} ignored: steerType {message.steerType} is not supported "
            f"(0 skid steering; 1 wheel steering angles needs steered wheels)",
        )
        return
    _drive(
        context,
        row,
        SideEffortCommand(
            throttle=float(message.throttle),
            skid_steering=float(message.skidSteering),
            brake=float(message.brake),
        ),
    )


def on_gv_state_cmd(context: BridgeContext, row: Row, message: morai_26_r1.GVStateCmd) -> None:
    """/gv_state_cmd: target forward speed (m/s) and yaw rate (rad/s) (latCtrlType 0)."""
    if message.latCtrlType != LAT_CTRL_ANGULAR_VELOCITY:
        context.warn_throttled(
            f"{row.name}: latCtrlType {message.latCtrlType}",
            f"{row.name} ignored: latCtrlType {message.latCtrlType} is not supported "
            f"(0 angular velocity; 1 steering angles needs steered wheels)",
        )
        return
    _drive(
        context,
        row,
        BodyVelocityCommand(
            linear=float(message.targetLongitudinalVelocity),
            angular=float(message.targetAngularVelocity),
        ),
    )


def on_webot_cmd(context: BridgeContext, row: Row, twist: standard.Twist) -> None:
    """/commands/vel: linear.x (m/s) and angular.z (rad/s); a ground vehicle has no other
    degrees of freedom, so the other components are not read."""
    _drive(
        context,
        row,
        BodyVelocityCommand(linear=float(twist.linear.x), angular=float(twist.angular.z)),
    )
