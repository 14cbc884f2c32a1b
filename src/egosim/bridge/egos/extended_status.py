"""The extended status rows of morai_msgs 26.r1: EgoVehicleStatusExtended and
ObjectStatusListExtended, off by default (MORAI documents no default topic for them;
egosim's names are /Ego_topic_extended and /Object_topic_extended).

Units as in the base messages: degrees, km/h for object velocities, m. Rates the world
does not carry (the steering wheel angle's speed, an object's yaw rate) are the change
of the angle since this row's previous message, over the simulation time between them.
Wheel speeds are the speed of each wheel's contact point along the wheel's heading, m/s.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from ...sensors.rotation import quaternion_from_euler
from ...world.map.projection import LaneProjections
from ...world.traffic import ObjectState
from ...world.vehicle import Vehicle, VehicleStatus
from ..context import BridgeContext
from ..protocol.messages import quaternion
from ..protocol.table import Row
from ..protocol.units import deg
from ..scene.objects import object_status_fields
from .ego import ego_motion_fields

if TYPE_CHECKING:
    from ...msgs.typed import morai_26_r1

FRONT, REAR = 0, 1


def wheel_speeds(vehicle: Vehicle, status: VehicleStatus) -> tuple[float, float, float, float]:
    """(front left, front right, rear left, rear right) contact-point speeds along each
    wheel's heading (m/s): the rigid body's velocity at the wheel, turned by its steer.
    The status's velocity is the reference point's, the rear axle's midpoint."""
    model = vehicle.model
    vx, vy, _ = status.velocity
    r = status.yaw_rate
    speeds = []
    for axle_x, steer in (
        (model.wheelbase, status.front_steer),
        (0.0, status.rear_steer),
    ):
        for side_y in (model.track_width / 2.0, -model.track_width / 2.0):
            wx, wy = vx - r * side_y, vy + r * axle_x
            speeds.append(wx * math.cos(steer) + wy * math.sin(steer))
    return speeds[0], speeds[1], speeds[2], speeds[3]


def publish_ego_status_extended(
    context: BridgeContext, row: Row
) -> morai_26_r1.EgoVehicleStatusExtended:
    """/Ego_topic_extended: the ego /Ego_topic reports, with wheel speeds and rates."""
    world = context.world
    index = context.session.camera_index if context.session.camera_index < len(world.egos) else 0
    ego = world.egos[index]
    status = world.ego_status(index)
    vehicle = ego.vehicle
    fl, fr, rl, rr = (
        wheel_speeds(vehicle, status) if isinstance(vehicle, Vehicle) else (status.speed,) * 4
    )
    steer_rate = context.session.angle_rates.rate(
        ("steer", ego.unique_id), status.front_steer, world.sim_time
    )
    profile = context.profile
    return profile.message("morai_msgs/EgoVehicleStatusExtended").new(
        header=context.header(),
        **ego_motion_fields(profile, ego.unique_id, status),
        wheel_angle=deg(status.front_steer),
        wheel_angle_speed=deg(steer_rate),
        FL_wheel_speed=fl,
        FR_wheel_speed=fr,
        RL_wheel_speed=rl,
        RR_wheel_speed=rr,
        yaw_rate=deg(status.yaw_rate),
    )


def publish_object_list_extended(
    context: BridgeContext, row: Row
) -> morai_26_r1.ObjectStatusListExtended:
    """/Object_topic_extended: /Object_topic's objects with orientation, turn signal, their
    lane (global_path_info: the lane id they are on), lane departure and distances to the
    lane's boundaries, and yaw rate."""
    world = context.world
    listing = world.object_list(context.session.camera_index)
    states = [*listing.npcs, *listing.pedestrians, *listing.obstacles]
    extended: list[morai_26_r1.ObjectStatusExtended] = []
    if states:
        positions = [s.position[:2] for s in states]
        lanes = world.map.project_many(positions, [s.heading for s in states])
        extended = [_extended(context, s, lanes, k) for k, s in enumerate(states)]
    n_npcs, n_walkers = len(listing.npcs), len(listing.pedestrians)
    return context.profile.message("morai_msgs/ObjectStatusListExtended").new(
        header=context.header(),
        num_of_npcs=listing.num_npcs,
        num_of_pedestrian=listing.num_pedestrians,
        num_of_obstacle=listing.num_obstacles,
        npc_list=extended[:n_npcs],
        pedestrian_list=extended[n_npcs : n_npcs + n_walkers],
        obstacle_list=extended[n_npcs + n_walkers :],
    )


def _extended(
    context: BridgeContext, state: ObjectState, lanes: LaneProjections, k: int
) -> morai_26_r1.ObjectStatusExtended:
    profile = context.profile
    world = context.world
    lane_id = lanes.lane_ids[int(lanes.lane_index[k])]
    departed = bool(np.abs(lanes.lateral[k]) > lanes.width[k] / 2.0)
    yaw_rate = context.session.angle_rates.rate(
        ("yaw", state.unique_id), state.heading, world.sim_time
    )
    return profile.message("morai_msgs/ObjectStatusExtended").new(
        **object_status_fields(profile, state),
        orientation=quaternion(profile, quaternion_from_euler(0.0, 0.0, state.heading)),
        turn_signal=_turn_signal(context, state.unique_id),
        global_path_info=[lane_id],
        lane_departure=int(departed),
        distance_left_lane=float(lanes.distance_left[k]),
        distance_right_lane=float(lanes.distance_right[k]),
        object_yaw_rate=deg(yaw_rate),
    )


def _turn_signal(context: BridgeContext, unique_id: int) -> int:
    """An NPC ghost's turn signal as placed, another ego's lamps; 0 for the rest."""
    ghosts = context.world.npc_ghosts
    if unique_id in ghosts:
        return int(ghosts.get(unique_id).turn_signal)
    ego = next((ego for ego in context.world.egos if ego.unique_id == unique_id), None)
    return 0 if ego is None else context.ego_session(ego).lamps.turn_signal
