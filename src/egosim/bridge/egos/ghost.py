"""Ghost mode: GhostMessage places the main ego, NpcGhostCmd places NPC vehicles.

GhostMessage (the ego input when the network settings choose GhostCtrlCmd): position
(m) is the point EgoVehicleStatus.position reports, rotation is roll, pitch, yaw in deg,
velocity km/h, steering_angle the front wheel angle in deg. Each message teleports the
ego there; until the next one the ego holds that speed and steering (a velocity-mode
command), so a log replayed at any rate gives a smooth trajectory.

NpcGhostCmd: each NpcGhostInfo places one NPC by unique_id. position is the footprint
centre (the point ObjectStatus.position reports), rpy.z the heading in deg (NPCs stay
level: roll and pitch are not modelled), vehicle_speed km/h along the heading,
steering_angle deg. Semantics and the lamps' whereabouts are in docs/protocol.md.
"""

from __future__ import annotations

import logging
import math
from typing import TYPE_CHECKING

from ...world.traffic.ghosts import GhostPlacement, NpcGhosts, TurnSignal
from ...world.vehicle import (
    ControlCommand,
    LongitudinalMode,
    Pose,
    UnknownVehicleModelError,
    Vehicle,
    vehicle_model,
)
from ..context import BridgeContext
from ..protocol.table import Row
from ..protocol.units import mps, rad
from .ground_vehicle import commanded_main_vehicle

if TYPE_CHECKING:
    from ...msgs.typed import morai_26_r1

log = logging.getLogger(__name__)


def _finite(*values: float) -> bool:
    return all(math.isfinite(v) for v in values)


def on_ghost_ctrl_cmd(context: BridgeContext, row: Row, message: morai_26_r1.GhostMessage) -> None:
    """/ghost_ctrl_cmd: teleport the main ego while its control mode is external."""
    vehicle = commanded_main_vehicle(context, row, Vehicle)
    if vehicle is None:
        return
    position, rotation = message.position, message.rotation
    values = (position.x, position.y, position.z, rotation.x, rotation.y, rotation.z)
    if not _finite(*values, message.velocity, message.steering_angle):
        log.error("%s ignored: a non-finite position, rotation, speed or angle", row.name)
        return
    if message.velocity < 0.0:
        log.error("%s ignored: velocity %s km/h is negative", row.name, message.velocity)
        return
    pose = Pose(position.x, position.y, position.z, *(rad(a) for a in values[3:]))
    speed, steer = mps(message.velocity), rad(message.steering_angle)
    vehicle.teleport(pose, speed, steer)
    vehicle.command(
        ControlCommand(mode=LongitudinalMode.VELOCITY, velocity=speed, front_steer=steer)
    )


def on_npc_ghost(context: BridgeContext, row: Row, message: morai_26_r1.NpcGhostCmd) -> None:
    """/NpcGhost_Topic: place the listed NPCs; bad entries are logged and skipped."""
    world = context.world
    simulated = dict(zip((int(i) for i in world.npcs.unique_ids), world.npcs.names, strict=True))
    placements = []
    for info in message.npc_list:
        placement = _placement(row, info, simulated, world.npc_ghosts)
        if placement is not None:
            placements.append(placement)
    for unique_id in world.place_npc_ghosts(placements):
        log.error("%s: unique_id %d belongs to an ego, pedestrian or obstacle", row.name, unique_id)


def _placement(
    row: Row, info: morai_26_r1.NpcGhostInfo, simulated: dict[int, str], ghosts: NpcGhosts
) -> GhostPlacement | None:
    unique_id = int(info.unique_id)
    position, rpy = info.position, info.rpy
    values = (position.x, position.y, position.z, rpy.z, info.vehicle_speed, info.steering_angle)
    if not _finite(*values):
        log.error("%s: NPC %d has a non-finite position, angle or speed", row.name, unique_id)
        return None
    if info.turn_signal not in TurnSignal.__members__.values():
        log.error("%s: NPC %d turn_signal %s is not 0..3", row.name, unique_id, info.turn_signal)
        return None
    if unique_id in ghosts:
        model = ghosts.get(unique_id).model
    else:
        # An NPC taken over keeps its own body; a new one is built from the named model.
        name = simulated.get(unique_id, info.name)
        try:
            model = vehicle_model(name)
        except UnknownVehicleModelError as error:
            log.error("%s: NPC %d not spawned: %s", row.name, unique_id, error)
            return None
    return GhostPlacement(
        unique_id,
        model,
        (position.x, position.y, position.z),
        rad(rpy.z),
        mps(info.vehicle_speed),
        rad(info.steering_angle),
        TurnSignal(int(info.turn_signal)),
        bool(info.brake_light),
    )
