"""A synthetic drive with a closed-form trajectory, recorded as egosim records.

The ego circles the origin counter-clockwise (radius 50 m, 10 m/s), so its
heading passes through +-180 deg; NPCs and a pedestrian move in straight
lines. Every recorded value is a function of time, so a replay can be checked
against the truth at any instant.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from egosim.msgs import get_profile
from egosim.replay import BagRecorder

PROFILE = get_profile("26.r1")
EGO = PROFILE.message("morai_msgs/EgoVehicleStatus")
OBJECTS = PROFILE.message("morai_msgs/ObjectStatusList")
CONTROL = PROFILE.message("morai_msgs/CtrlCmd")
VECTOR = "geometry_msgs/msg/Vector3"

START_NS = 1_700_000_000 * 10**9  # header stamps and receive times of the first messages
DURATION_S = 10.0
EGO_HZ = 50
OBJECTS_HZ = 20
CONTROL_HZ = 10
RADIUS_M = 50.0
SPEED_MS = 10.0
OMEGA = SPEED_MS / RADIUS_M  # rad/s
START_ANGLE = math.radians(60.0)  # heading starts at 150 deg and crosses 180 at t = 2.6 s


@dataclass(frozen=True)
class MovingObject:
    unique_id: int
    list_name: str  # npc_list or pedestrian_list
    type_code: int
    start: tuple[float, float]  # m
    velocity: tuple[float, float]  # m/s
    until_s: float = math.inf  # last listed before this time

    def position(self, t: float) -> tuple[float, float, float]:
        return (self.start[0] + self.velocity[0] * t, self.start[1] + self.velocity[1] * t, 0.0)

    def heading_deg(self) -> float:
        return math.degrees(math.atan2(self.velocity[1], self.velocity[0]))


MOVING_OBJECTS = (
    MovingObject(11, "npc_list", 1, (0.0, 10.0), (8.0, 0.0)),
    MovingObject(12, "npc_list", 1, (100.0, -3.5), (-12.0, 1.0)),
    MovingObject(13, "npc_list", 1, (-20.0, 0.0), (0.0, 5.0), until_s=5.0),
    MovingObject(21, "pedestrian_list", 0, (5.0, 5.0), (1.2, -0.6)),
)


def ego_angle(t: float) -> float:
    """Polar angle of the ego on its circle, rad."""
    return START_ANGLE + OMEGA * t


def ego_position(t: float) -> tuple[float, float, float]:
    return (RADIUS_M * math.cos(ego_angle(t)), RADIUS_M * math.sin(ego_angle(t)), 0.0)


def ego_heading(t: float) -> float:
    """Heading, rad in [-pi, pi): the tangent of the counter-clockwise circle."""
    return (ego_angle(t) + math.pi / 2 + math.pi) % (2 * math.pi) - math.pi


def ego_pedal(t: float) -> float:
    return 0.5 + 0.4 * math.sin(t)


def control_velocity_kmh(t: float) -> float:
    return 36.0 + t


def stamp(t: float) -> int:
    return START_NS + round(t * 1e9)


def times(rate_hz: int) -> list[float]:
    return [k / rate_hz for k in range(int(DURATION_S * rate_hz) + 1)]


def vector(x: float, y: float, z: float) -> Any:
    return PROFILE.message(VECTOR).make(x=x, y=y, z=z)


def header(t: float, seq: int) -> Any:
    message = EGO.new().header
    message.seq = seq
    message.stamp.sec, message.stamp.nanosec = divmod(stamp(t), 10**9)
    message.frame_id = "map"
    return message


def ego_message(t: float, seq: int) -> Any:
    return EGO.new(
        header=header(t, seq),
        unique_id=-1,
        position=vector(*ego_position(t)),
        velocity=vector(SPEED_MS, 0.0, 0.0),
        acceleration=vector(0.0, SPEED_MS * OMEGA, 0.0),
        heading=math.degrees(ego_heading(t)),
        accel=ego_pedal(t),
        brake=0.0,
        front_steer_angle=math.degrees(math.atan(2.7 / RADIUS_M)),
    )


def objects_message(t: float, seq: int) -> Any:
    lists: dict[str, list[Any]] = {"npc_list": [], "pedestrian_list": []}
    status_type = PROFILE.message("morai_msgs/ObjectStatus").make
    for obj in MOVING_OBJECTS:
        if t >= obj.until_s:
            continue
        lists[obj.list_name].append(
            status_type(
                unique_id=obj.unique_id,
                type=obj.type_code,
                name=f"object#{obj.unique_id}",
                heading=obj.heading_deg(),
                velocity=vector(obj.velocity[0] * 3.6, obj.velocity[1] * 3.6, 0.0),
                acceleration=vector(0.0, 0.0, 0.0),
                size=vector(1.8, 4.5, 1.5),
                position=vector(*obj.position(t)),
            )
        )
    return OBJECTS.new(
        header=header(t, seq),
        num_of_npcs=len(lists["npc_list"]),
        num_of_pedestrian=len(lists["pedestrian_list"]),
        npc_list=lists["npc_list"],
        pedestrian_list=lists["pedestrian_list"],
    )


def control_message(t: float) -> Any:
    return CONTROL.new(
        longlCmdType=2, accel=0.0, brake=0.0, front_steer=0.05, velocity=control_velocity_kmh(t)
    )


def drive_messages() -> list[tuple[float, str, Any, bytes]]:
    """(time s, topic, type, serialised message) of the whole drive, in time order."""
    messages = [
        (t, "/Ego_topic", EGO, EGO.serialize(ego_message(t, k)))
        for k, t in enumerate(times(EGO_HZ))
    ]
    messages += [
        (t, "/Object_topic", OBJECTS, OBJECTS.serialize(objects_message(t, k)))
        for k, t in enumerate(times(OBJECTS_HZ))
    ]
    messages += [
        (t, "/ctrl_cmd", CONTROL, CONTROL.serialize(control_message(t))) for t in times(CONTROL_HZ)
    ]
    return sorted(messages, key=lambda item: item[0])


def record_drive(path: Path, **recorder_options: Any) -> Path:
    """The whole drive recorded by BagRecorder, receive time = header time."""
    with BagRecorder(path, **recorder_options) as recorder:
        handles = {
            topic: recorder.add_connection(topic, kind.name, kind.md5sum, kind.definition)
            for topic, kind in (
                ("/Ego_topic", EGO),
                ("/Object_topic", OBJECTS),
                ("/ctrl_cmd", CONTROL),
            )
        }
        for t, topic, _, data in drive_messages():
            recorder.write(handles[topic], stamp(t), data)
    return path


def expected_counts() -> dict[str, int]:
    return {
        "/Ego_topic": len(times(EGO_HZ)),
        "/Object_topic": len(times(OBJECTS_HZ)),
        "/ctrl_cmd": len(times(CONTROL_HZ)),
    }
