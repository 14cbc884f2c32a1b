"""Rosbag replay on the wire: /Morai_SimProc in, MoraiSimProcStatus and ReplayInfo out.

The replay session (egosim.replay) is pure logic over a playback clock; this
module advances it with the loop, makes the world show the selected targets
of the bag (world.show_recorded) and reports the session's state. Headers
carry the simulator's clock, like every other row; the bag's own time is the
playback clock.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, TypedDict

from ...replay import BagTimeline, CommandResult, Mode, ObjectState, ReplayTopics
from ...sensors.rotation import quaternion_from_euler
from ...world.traffic import ObjectType
from ..context import MAP_FRAME, BridgeContext
from ..protocol.messages import quaternion, vector3
from ..protocol.network import NetworkSettings
from ..protocol.table import Row
from ..protocol.units import deg
from ..scene.objects import object_status
from .replayed_scene import recorded_scene, shows_nothing_recorded, world_objects

if TYPE_CHECKING:
    from ...msgs.typed import morai_26_r1, standard

# The yaw rate ReplayInfo reports is the slope of the recorded heading over this span (s).
YAW_RATE_SPAN_S = 0.002


class RecordedEgoFields(TypedDict, total=False):
    """ReplayInfo's fields of the recorded ego: none when the bag has no ego."""

    ego_acc: float
    ego_brake: float
    ego_steer: float
    orientation: standard.Quaternion
    linear_acceleration: standard.Vector3
    angular_velocity: standard.Vector3


def replay_topics(settings: NetworkSettings) -> ReplayTopics:
    """Where the replayed rows are recorded: their names in the effective table."""
    return ReplayTopics(
        ego=settings.row("ego_status").name,
        objects=settings.row("object_status").name,
        control=settings.row("ctrl_cmd").name,
    )


def show_replay(context: BridgeContext) -> None:
    """Make the world show the session's frame (nothing, in simulation mode)."""
    session = context.replay
    frame = session.frame()
    if frame is None and shows_nothing_recorded(context.world.recorded):
        return  # simulating, as before: the world shows its own agents already
    context.world.show_recorded(recorded_scene(frame, session.targets))


def advance_replay(context: BridgeContext, dt: float) -> None:
    """Before each physics step of `dt` s: move the playback clock and show where it is."""
    if context.world.paused:
        return
    context.replay.advance(dt)
    show_replay(context)


def serve_sim_proc(
    context: BridgeContext, row: Row, request: morai_26_r1.MoraiSimProcSrvRequest
) -> morai_26_r1.MoraiSimProcSrvResponse:
    """/Morai_SimProc: apply the MoraiSimProcHandle; result true only on 0x01 success."""
    received_ns = context.stamp_ns()
    result = context.replay.handle(request.request, received_ns=received_ns)
    show_replay(context)
    profile = context.profile
    return profile.message("morai_msgs/MoraiSimProcSrvResponse").new(
        response=profile.message("morai_msgs/MoraiSrvResponse").new(
            result=result is CommandResult.SUCCESS
        )
    )


def publish_sim_proc_status(context: BridgeContext, row: Row) -> bytes:
    """/sim/process/state/msg/MoraiSimProcStatus: always, in simulation mode too; its
    bytes (the header's seq and stamp written by the outlet)."""
    status = context.replay.status()
    pack = context.profile.message("morai_msgs/MoraiSimProcStatus").flat().pack
    return pack(
        0, 0, 0, MAP_FRAME,
        *divmod(status.latest_command_time_ns, 1_000_000_000),
        int(status.command_result), int(status.current_mode), int(status.current_status),
    )  # fmt: skip


def publish_replay_info(context: BridgeContext, row: Row) -> morai_26_r1.ReplayInfo | None:
    """/ReplayInfo_topic, during replay only: the bag's ego inputs and objects at the
    playback clock, whichever targets are replayed (ReplayInfo describes the bag)."""
    session = context.replay
    timeline = session.timeline
    if session.mode is not Mode.REPLAY or timeline is None:
        return None
    frame = timeline.sample(session.playback_time)
    profile = context.profile
    ego = frame.ego
    fields: RecordedEgoFields = {}
    if ego is not None:
        fields = {
            "ego_acc": ego.accel_pedal,
            "ego_brake": ego.brake_pedal,
            "ego_steer": deg(ego.front_steer),
            "orientation": quaternion(profile, quaternion_from_euler(0.0, 0.0, ego.heading)),
            "linear_acceleration": vector3(profile, ego.acceleration),
            "angular_velocity": vector3(
                profile, (0.0, 0.0, recorded_yaw_rate(timeline, frame.time))
            ),
        }

    def listed(recorded: Sequence[ObjectState], kind: ObjectType) -> list[morai_26_r1.ObjectStatus]:
        return [object_status(profile, o) for o in world_objects(recorded, kind)]

    return profile.message("morai_msgs/ReplayInfo").new(
        header=context.header(),
        num_of_npcs=len(frame.npcs),
        num_of_pedestrian=len(frame.pedestrians),
        num_of_obstacle=len(frame.obstacles),
        npc_list=listed(frame.npcs, ObjectType.NPC_VEHICLE),
        pedestrian_list=listed(frame.pedestrians, ObjectType.PEDESTRIAN),
        obstacle_list=listed(frame.obstacles, ObjectType.OBSTACLE),
        **fields,
    )


def recorded_yaw_rate(timeline: BagTimeline, t: float) -> float:
    """rad/s: the recorded heading's slope around `t` s (EgoVehicleStatus has no yaw rate)."""
    assert timeline.ego is not None
    start = max(t - YAW_RATE_SPAN_S / 2, 0.0)
    end = min(t + YAW_RATE_SPAN_S / 2, timeline.duration)
    if end <= start:
        return 0.0
    turned = timeline.ego.sample(end).heading - timeline.ego.sample(start).heading
    return math.remainder(turned, math.tau) / (end - start)
