"""Objects around the ego: ObjectStatusList, CollisionData, VehicleCollisionData.

ObjectStatus carries heading in deg, velocity in km/h and acceleration in m/s^2,
both vectors in the object's own frame (x forward, y left), so `velocity.x`
is its speed as MORAI clients read it; position is the footprint centre in the
map frame; size is (length, width, height) in m.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from typing import TYPE_CHECKING, TypedDict

import numpy as np

from ...world.arrays import IntArray
from ...world.collision import VehicleCollision
from ...world.traffic import ObjectState, ObjectTable
from ..context import MAP_FRAME, BridgeContext
from ..protocol.messages import vector3
from ..protocol.table import Row
from ..protocol.units import heading_deg, kmh, swap_length_width

if TYPE_CHECKING:
    from ...msgs.typed import morai_26_r1, standard
    from ..protocol.releases import CanonicalProfile


def to_object_frame(vector: Sequence[float], heading: float) -> tuple[float, float, float]:
    """A map-frame vector in the frame of an object heading `heading` (rad)."""
    return _turned(vector, math.cos(heading), math.sin(heading))


def _turned(vector: Sequence[float], c: float, s: float) -> tuple[float, float, float]:
    """`vector` turned by the heading whose cosine and sine are `c` and `s`."""
    x, y, z = vector
    return (c * x + s * y, -s * x + c * y, z)


def _status_numbers(
    heading: float,
    velocity: Sequence[float],
    acceleration: Sequence[float],
    size: Sequence[float],
    position: Sequence[float],
) -> tuple[float, ...]:
    """ObjectStatus's numbers after its name, in protocol units and in wire order:
    heading (deg), velocity (km/h) and acceleration in the object's frame, size (width,
    length, height), position."""
    c, s = math.cos(heading), math.sin(heading)
    vx, vy, vz = _turned(velocity, c, s)
    return (
        heading_deg(heading),
        *(kmh(vx), kmh(vy), kmh(vz)),
        *_turned(acceleration, c, s),
        *swap_length_width(size),
        *position,
    )


class ObjectStatusFields(TypedDict):
    """The fields ObjectStatus and ObjectStatusExtended share."""

    unique_id: int
    type: int
    name: str
    heading: float
    velocity: standard.Vector3
    acceleration: standard.Vector3
    size: standard.Vector3
    position: standard.Vector3


def object_status_fields(profile: CanonicalProfile, state: ObjectState) -> ObjectStatusFields:
    """The fields ObjectStatus and ObjectStatusExtended share, in protocol units."""
    heading, *numbers = _status_numbers(
        state.heading, state.velocity, state.acceleration, state.size, state.position
    )
    return {
        "unique_id": state.unique_id,
        "type": int(state.object_type),
        "name": state.name,
        "heading": heading,
        "velocity": vector3(profile, numbers[0:3]),
        "acceleration": vector3(profile, numbers[3:6]),
        "size": vector3(profile, numbers[6:9]),
        "position": vector3(profile, numbers[9:12]),
    }


def object_status(profile: CanonicalProfile, state: ObjectState) -> morai_26_r1.ObjectStatus:
    # Every field is given: the class itself, not MessageType.new (a list has dozens).
    return profile.message("morai_msgs/ObjectStatus").make(**object_status_fields(profile, state))


def _object_statuses(profile: CanonicalProfile, table: ObjectTable, rows: IntArray) -> list[bytes]:
    """The ObjectStatus bytes of the objects at `rows` of `table` (each column read at
    once, each object packed without building a message)."""
    names = table.names
    return _status_bytes(
        profile,
        zip(
            table.unique_ids[rows].tolist(),
            table.object_types[rows].tolist(),
            [names[row] for row in rows.tolist()],
            table.headings[rows].tolist(),
            table.velocities[rows].tolist(),
            table.accelerations[rows].tolist(),
            table.sizes[rows].tolist(),
            table.positions[rows].tolist(),
            strict=True,
        ),
    )


def _state_statuses(profile: CanonicalProfile, states: Iterable[ObjectState]) -> list[bytes]:
    """The ObjectStatus bytes of `states`."""
    return _status_bytes(
        profile,
        (
            (
                s.unique_id,
                int(s.object_type),
                s.name,
                s.heading,
                s.velocity,
                s.acceleration,
                s.size,
                s.position,
            )
            for s in states
        ),
    )


_StatusFields = tuple[
    int, int, str, float, Sequence[float], Sequence[float], Sequence[float], Sequence[float]
]
"""An object's id, type code, name, heading, velocity, acceleration, size and position (SI)."""


def _status_bytes(profile: CanonicalProfile, objects: Iterable[_StatusFields]) -> list[bytes]:
    """Each object's ObjectStatus bytes, its numbers in protocol units."""
    pack = profile.message("morai_msgs/ObjectStatus").flat().pack
    return [
        pack(
            unique_id, kind, name, *_status_numbers(heading, velocity, acceleration, size, position)
        )
        for unique_id, kind, name, heading, velocity, acceleration, size, position in objects
    ]


def publish_object_list(context: BridgeContext, row: Row) -> bytes:
    """/Object_topic: counts of everything spawned; the N closest objects, closest first
    (from the position /Ego_topic reports to each reported position). Its bytes (the
    outlet stamps them), from the tick's object table."""
    nearest = context.world.nearest_objects(
        context.session.camera_index, scene=context.scene_objects()
    )
    lists = (nearest.npcs, nearest.pedestrians, nearest.obstacles)
    statuses = _object_statuses(context.profile, nearest.table, np.concatenate(lists))
    npcs, walkers = len(nearest.npcs), len(nearest.npcs) + len(nearest.pedestrians)
    return context.profile.message("morai_msgs/ObjectStatusList").flat().pack(
        0, 0, 0, MAP_FRAME,  # header: seq and stamp written by the outlet
        nearest.num_npcs, nearest.num_pedestrians, nearest.num_obstacles,
        statuses[:npcs], statuses[npcs:walkers], statuses[walkers:],
    )  # fmt: skip


EGO_COLLISIONS = "ego_collisions"
VEHICLE_COLLISIONS = "vehicle_collisions"


def publish_collision(context: BridgeContext, row: Row) -> bytes:
    """/CollisionData: the main ego's collisions that began since the row's previous
    message, then the objects it still touches (a contact is reported as long as it lasts).

    The previous message is the previous one due, whether anyone listened or not
    (pass_collisions): a subscriber that joins late gets no collision older than one
    period. An empty collision_object list means no collision and no contact;
    global_offset_* is the position of the most recent collided object, in every message
    after it (zeros before the first).
    """
    world = context.world
    ego_id = world.egos[0].unique_id
    new = [
        c.other
        for c in context.unreported(EGO_COLLISIONS, world.ego_collision_log)
        if c.ego_id == ego_id
    ]
    listed = {other.unique_id for other in new}
    lasting = [o for o in world.ego_contacts.get(ego_id, []) if o.unique_id not in listed]
    latest = world.ego_collision(0)
    offset = latest.other.position if latest is not None else (0.0, 0.0, 0.0)
    pack = context.profile.message("morai_msgs/CollisionData").flat().pack
    touched = _state_statuses(context.profile, new + lasting)
    # header (seq and stamp written by the outlet), global_offset_*, collision_object,
    # collision_objecta (unused)
    return pack(0, 0, 0, MAP_FRAME, *(float(v) for v in offset), touched, [])


def publish_vehicle_collisions(context: BridgeContext, row: Row) -> bytes:
    """/VehicleCollisionData: NPC-NPC collisions that began since the last message, then
    the NPC-NPC contacts that last."""
    profile = context.profile
    collision = profile.message("morai_msgs/VehicleCollision").flat().pack
    new = context.unreported(VEHICLE_COLLISIONS, context.world.vehicle_collisions)
    listed = {_pair(c) for c in new}
    new += [c for c in context.world.vehicle_contacts if _pair(c) not in listed]
    collisions = [collision(_state_statuses(profile, c.vehicles)) for c in new]
    pack = profile.message("morai_msgs/VehicleCollisionData").flat().pack
    return pack(0, 0, 0, MAP_FRAME, collisions)  # header: seq and stamp by the outlet


def pass_collisions(context: BridgeContext, row: Row) -> None:
    """/CollisionData due with no one listening: its new collisions count as reported."""
    context.unreported(EGO_COLLISIONS, context.world.ego_collision_log)


def pass_vehicle_collisions(context: BridgeContext, row: Row) -> None:
    """/VehicleCollisionData due with no one listening: the same."""
    context.unreported(VEHICLE_COLLISIONS, context.world.vehicle_collisions)


def _pair(collision: VehicleCollision) -> frozenset[int]:
    return frozenset(v.unique_id for v in collision.vehicles)
