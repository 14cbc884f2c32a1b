"""Replay through the protocol: a drive recorded with `egosim run --record` is played back
by /Morai_SimProc and the simulator's own topics report the recorded trajectories."""

from __future__ import annotations

import bisect
import math
import shutil
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest
from rosbags.rosbag1 import Reader
from rosbags.typesys.msg import denormalize_msgtype

from egosim.msgs import get_profile
from tests.e2e.driver import RospyDriver

pytestmark = pytest.mark.ros

EGO = ("/Ego_topic", "morai_msgs/EgoVehicleStatus")
OBJECTS = ("/Object_topic", "morai_msgs/ObjectStatusList")
CTRL = ("/ctrl_cmd", "morai_msgs/CtrlCmd")
STATUS = ("/sim/process/state/msg/MoraiSimProcStatus", "morai_msgs/MoraiSimProcStatus")
REPLAY_INFO = ("/ReplayInfo_topic", "morai_msgs/ReplayInfo")
SIM_PROC = ("/Morai_SimProc", "morai_msgs/MoraiSimProcSrv")

# MoraiSimProcHandle codes, as the protocol document writes them.
PLAY = 1
LOAD, SET_TARGET, SET_SPEED = 0x0001, 0x0010, 0x1000
TARGET_EGO, TARGET_NPC, TARGET_PEDESTRIAN = 0x0001, 0x0010, 0x0100
SUCCESS, BAG_LOAD_FAILED = 0x01, 0x20
REPLAY_MODE, AT_END = 0x10, 0x20

RECORD_S = 20.0
TOLERANCE_M = 0.01
# The lists of ObjectStatusList and the target that replays each.
LISTS_OF_TARGET = {
    TARGET_EGO: (),
    TARGET_NPC: ("npc_list", "obstacle_list"),
    TARGET_PEDESTRIAN: ("pedestrian_list",),
}
PROFILE = get_profile("26.r1")


def read_bag(path: Path) -> dict[str, list[tuple[int, Any]]]:
    """Every message of the bag by topic: (receive time ns, decoded message)."""
    topics: dict[str, list[tuple[int, Any]]] = {}
    with Reader(path) as reader:
        for connection, received, raw in reader.messages():
            message_type = PROFILE.message(denormalize_msgtype(connection.msgtype))
            topics.setdefault(connection.topic, []).append(
                (received, message_type.deserialize(raw))
            )
    return topics


def stamp_ns(message: Any) -> int:
    return message.header.stamp.sec * 10**9 + message.header.stamp.nanosec


@dataclass
class Recording:
    """The ego and object positions of a bag, on the bag's header clock."""

    start_ns: int
    end_ns: int
    ego_times: list[int]
    ego_xy: list[tuple[float, float]]
    object_times: list[int]
    object_lists: list[dict[str, dict[int, tuple[float, float]]]]

    @classmethod
    def of(cls, path: Path) -> Recording:
        bag = read_bag(path)
        egos = sorted((stamp_ns(m), m) for _, m in bag[EGO[0]])
        lists = sorted(((stamp_ns(m), m) for _, m in bag[OBJECTS[0]]), key=lambda p: p[0])
        # Replay time runs from the first replayed message; egosim stamps commands it
        # receives on the same clock as the headers.
        times = [egos[0][0], lists[0][0], *(r for r, _ in bag.get(CTRL[0], [])[:1])]
        ends = [egos[-1][0], lists[-1][0], *(r for r, _ in bag.get(CTRL[0], [])[-1:])]
        return cls(
            min(times),
            max(ends),
            [t for t, _ in egos],
            [(m.position.x, m.position.y) for _, m in egos],
            [t for t, _ in lists],
            [
                {
                    name: {o.unique_id: (o.position.x, o.position.y) for o in getattr(m, name)}
                    for name in ("npc_list", "pedestrian_list", "obstacle_list")
                }
                for _, m in lists
            ],
        )

    @property
    def duration_s(self) -> float:
        return (self.end_ns - self.start_ns) / 1e9

    def ego_at(self, t_ns: float) -> tuple[float, float]:
        """The ego's recorded position, linear between the messages around t."""
        i, j, alpha = bracket(self.ego_times, t_ns)
        return lerp(self.ego_xy[i], self.ego_xy[j], alpha)

    def objects_at(self, t_ns: float, list_name: str) -> dict[int, tuple[float, float]]:
        """The latest list at or before t, each object moved towards the next list."""
        i, j, alpha = bracket(self.object_times, t_ns)
        here, there = self.object_lists[i][list_name], self.object_lists[j][list_name]
        return {
            uid: lerp(xy, there[uid], alpha) if uid in there else xy for uid, xy in here.items()
        }


def bracket(times: list[int], t: float) -> tuple[int, int, float]:
    i = max(bisect.bisect_right(times, t) - 1, 0)
    if i >= len(times) - 1:
        return i, i, 0.0
    return i, i + 1, (t - times[i]) / (times[i + 1] - times[i])


def lerp(a: tuple[float, float], b: tuple[float, float], alpha: float) -> tuple[float, float]:
    return (a[0] + alpha * (b[0] - a[0]), a[1] + alpha * (b[1] - a[1]))


def xy(vector: dict[str, float]) -> tuple[float, float]:
    return (vector["x"], vector["y"])


def sim_proc(client: RospyDriver, **fields: Any) -> bool:
    handle = {
        "sim_process_status": 0,
        "replay_option": 0,
        "rosbag_file_name": "",
        "replay_target_option": 0,
        "replay_speed": 1,
        "start_time": 0,
        **fields,
    }
    return client.call(*SIM_PROC, {"request": handle})["response"]["result"]


def status_at_end(client: RospyDriver, after: float) -> dict[str, Any]:
    """The first MoraiSimProcStatus at the end of a bag played by a command later than
    `after` (s), waiting generously."""
    since = 0
    for _ in range(600):
        received = client.messages(STATUS[0], since=since, count=1, timeout=60)
        since += len(received)
        for status in received:
            if status["current_status"] == AT_END and status["latest_command_time"] > after:
                return status
    raise AssertionError("the replay never reached the awaited status")


def record_drive(
    egosim: Callable[..., Any], rospy_client: Callable[..., RospyDriver], bag: Path
) -> None:
    """20 s of the default scenario with a scripted controller, recorded by egosim."""
    recording = egosim(
        "--clock", "sim", "--rtf", "0", "--duration", str(RECORD_S), "--record", str(bag)
    )
    driver = rospy_client(recording)
    # Accelerate while steering gently left, then brake: a curved drive that stops.
    driver.stream(*CTRL, {"longlCmdType": 1, "accel": 0.5, "front_steer": 0.03}, rate=50)
    driver.subscribe(*EGO)
    driver.messages(EGO[0], count=100, timeout=60)
    driver.stream(*CTRL, {"longlCmdType": 1, "brake": 0.3, "front_steer": -0.02}, rate=50)
    assert recording.process.wait(120) == 0


def replayed(client: RospyDriver, topic: str, since: int) -> list[dict[str, Any]]:
    return client.messages(topic, since=since, count=0, timeout=0)


def test_replayed_trajectories_match_the_recording(
    egosim: Callable[..., Any], rospy_client: Callable[..., RospyDriver], tmp_path: Path
) -> None:
    bag = tmp_path / "drive.bag"
    record_drive(egosim, rospy_client, bag)
    recording = Recording.of(bag)
    assert recording.duration_s == pytest.approx(RECORD_S, abs=0.1)
    recorded_ego_path = math.dist(recording.ego_xy[0], recording.ego_xy[-1])
    assert recorded_ego_path > 5.0, "the scripted controller should have moved the ego"

    player = egosim("--clock", "sim", "--rtf", "0")
    shutil.copy(bag, player.data_root / "drive.bag")
    client = rospy_client(player)
    for topic in (EGO, OBJECTS, STATUS):
        client.subscribe(*topic)
    client.messages(STATUS[0], count=1)
    commanded = -1.0

    for speed in (1, 4):
        for target in (TARGET_EGO, TARGET_NPC, TARGET_PEDESTRIAN):
            commanded = replay_and_compare(client, recording, speed, target, after=commanded)


def replay_and_compare(
    client: RospyDriver, recording: Recording, speed: int, target: int, after: float
) -> float:
    """Play the whole bag for one target at one speed; compare what the simulator reports
    with the recording at matched times. The time (s) the play command arrived."""
    since = {topic: len(replayed(client, topic, 0)) for topic in (EGO[0], OBJECTS[0])}
    assert sim_proc(
        client,
        sim_process_status=PLAY,
        replay_option=LOAD | SET_TARGET | SET_SPEED,
        rosbag_file_name="drive.bag",
        replay_target_option=target,
        replay_speed=speed,
    )
    end = status_at_end(client, after)
    assert end["command_result"] == SUCCESS
    assert end["current_mode"] == REPLAY_MODE
    commanded = end["latest_command_time"]
    # Playback starts at the command and runs `speed` bag seconds per simulated second.
    last = commanded + recording.duration_s / speed

    def matched(topic: str) -> list[tuple[float, dict[str, Any]]]:
        """Replayed messages with the bag time (ns) they show."""
        return [
            (recording.start_ns + (m["header"]["stamp"] - commanded) * speed * 1e9, m)
            for m in replayed(client, topic, since[topic])
            if commanded < m["header"]["stamp"] <= last
        ]

    egos, lists = matched(EGO[0]), matched(OBJECTS[0])
    case = f"{speed}x, target {target:#06x}"
    assert len(egos) >= 10 and len(lists) >= 10, case
    ego_errors = [math.dist(xy(m["position"]), recording.ego_at(t)) for t, m in egos]
    if target == TARGET_EGO:
        assert max(ego_errors) < TOLERANCE_M, case
    else:
        # The ego is not replayed: it keeps being simulated, and nobody drives it.
        assert max(ego_errors) > 1.0, case
    for list_name in LISTS_OF_TARGET[target]:
        errors = []
        for t, message in lists:
            expected = recording.objects_at(t, list_name)
            shown = {o["unique_id"]: xy(o["position"]) for o in message[list_name]}
            assert shown.keys() == expected.keys(), (case, list_name)
            errors += [math.dist(shown[uid], expected[uid]) for uid in expected]
        assert errors and max(errors) < TOLERANCE_M, (case, list_name)
    return commanded
