"""A replay frame (egosim.replay, SI) as the world's records: what the world shows and
what ReplayInfo lists.

Replayed objects come from ObjectStatus, whose velocity and acceleration are in
the object's own frame; the world keeps them in the map frame. This module is
the one place that turns a recorded object into a world ObjectState, so the
world's tables and ReplayInfo's lists agree.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from ...replay import EgoState, ReplayFrame, ReplayTargets
from ...replay import ObjectState as RecordedObject
from ...world.recorded_scene import RecordedEgo, RecordedScene
from ...world.traffic import ObjectState, ObjectTable, ObjectType
from ...world.vehicle import Pose
from ..protocol.units import swap_length_width
from ..scene.objects import to_object_frame


def world_object(recorded: RecordedObject, kind: ObjectType) -> ObjectState:
    """A recorded ObjectStatus entry of the list of `kind` as a world object."""
    # Rotating by -heading into "the object's frame" is rotating by +heading out of it.
    return ObjectState(
        unique_id=recorded.unique_id,
        object_type=kind,
        name=recorded.name,
        position=recorded.position,
        heading=recorded.heading,
        velocity=to_object_frame(recorded.velocity, -recorded.heading),
        acceleration=to_object_frame(recorded.acceleration, -recorded.heading),
        size=swap_length_width(recorded.size),
    )


def world_objects(recorded: Sequence[RecordedObject], kind: ObjectType) -> tuple[ObjectState, ...]:
    return tuple(world_object(r, kind) for r in recorded)


def object_table(objects: Sequence[ObjectState]) -> ObjectTable:
    n = len(objects)
    return ObjectTable(
        unique_ids=np.array([o.unique_id for o in objects], dtype=np.int64),
        object_types=np.array([int(o.object_type) for o in objects], dtype=np.int64),
        names=tuple(o.name for o in objects),
        positions=np.array([o.position for o in objects], dtype=np.float64).reshape(n, 3),
        headings=np.array([o.heading for o in objects], dtype=np.float64),
        velocities=np.array([o.velocity for o in objects], dtype=np.float64).reshape(n, 3),
        accelerations=np.array([o.acceleration for o in objects], dtype=np.float64).reshape(n, 3),
        sizes=np.array([o.size for o in objects], dtype=np.float64).reshape(n, 3),
    )


def recorded_ego(ego: EgoState) -> RecordedEgo:
    """EgoVehicleStatus's position is the vehicle's pose and its velocity body-frame."""
    x, y, z = ego.position
    return RecordedEgo(
        Pose(x=x, y=y, z=z, yaw=ego.heading),
        ego.velocity[0],
        ego.front_steer,
        ego.rear_steer,
        acceleration=(ego.acceleration[0], ego.acceleration[1], ego.acceleration[2]),
        accel_pedal=ego.accel_pedal,
        brake_pedal=ego.brake_pedal,
    )


def shows_nothing_recorded(scene: RecordedScene) -> bool:
    """`scene` is full simulation (RecordedScene()): no recording stands in for anything."""
    return (
        scene.ego is None
        and scene.npcs is None
        and scene.pedestrians is None
        and scene.obstacles is None
    )


def recorded_scene(frame: ReplayFrame | None, targets: ReplayTargets) -> RecordedScene:
    """What the world shows of `frame` (None: nothing, full simulation) for these targets.

    A target kind is shown even when the frame holds none of it (the recording
    had no such object at that time); obstacles follow the NPC vehicles.
    """
    if frame is None:
        return RecordedScene()

    def table(objects: Sequence[RecordedObject], kind: ObjectType) -> ObjectTable:
        return object_table(world_objects(objects, kind))

    return RecordedScene(
        ego=recorded_ego(frame.ego) if targets.ego and frame.ego is not None else None,
        npcs=table(frame.npcs, ObjectType.NPC_VEHICLE) if targets.npcs else None,
        pedestrians=table(frame.pedestrians, ObjectType.PEDESTRIAN)
        if targets.pedestrians
        else None,
        obstacles=table(frame.obstacles, ObjectType.OBSTACLE) if targets.npcs else None,
    )
