"""Replay through the protocol: a drive recorded with `egosim run --record` is played back
by /Morai_SimProc and the simulator's own topics report the recorded trajectories."""

from __future__ import annotations

import bisect
import math
import shutil
import time
import xmlrpc.client
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest
from rosbags.rosbag1 import Reader
from rosbags.typesys.msg import denormalize_msgtype

from egosim.msgs import get_profile
from tests.conftest import EVENT_TIMEOUT_S
from tests.e2e.driver import RospyDriver
from tests.waiting import until

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
SIMULATION_MODE, REPLAY_MODE, AT_END = 0x01, 0x10, 0x20

# The drive: ACCELERATE_S of throttle, then the brake; the ego stands well before RECORD_S.
RECORD_S = 10.0
ACCELERATE_S = 2.0
EGO_RATE_HZ = 50  # /Ego_topic's default rate
TOLERANCE_M = 0.01
# The lists of ObjectStatusList and the target that replays each.
LISTS_OF_TARGET = {
    TARGET_EGO: (),
    TARGET_NPC: ("npc_list", "obstacle_list"),
    TARGET_PEDESTRIAN: ("pedestrian_list",),
}
PROFILE = get_profile("26.r1")
# What the tests read of each recorded EgoVehicleStatus (heading and steering in deg).
EGO_FIELDS = ("x", "y", "heading", "accel", "brake", "front_steer")


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
    ego_rows: list[tuple[float, ...]]  # EGO_FIELDS
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
            [
                (m.position.x, m.position.y, m.heading, m.accel, m.brake, m.front_steer_angle)
                for _, m in egos
            ],
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

    def ego_at(self, t_ns: float) -> dict[str, float]:
        """The ego's recorded EGO_FIELDS, linear between the messages around t."""
        i, j, alpha = bracket(self.ego_times, t_ns)
        return dict(zip(EGO_FIELDS, lerp(self.ego_rows[i], self.ego_rows[j], alpha), strict=True))

    def ego_xy(self, t_ns: float) -> tuple[float, float]:
        ego = self.ego_at(t_ns)
        return (ego["x"], ego["y"])

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


def lerp(a: tuple[float, ...], b: tuple[float, ...], alpha: float) -> tuple[float, ...]:
    return tuple(p + alpha * (q - p) for p, q in zip(a, b, strict=True))


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


def status_after(
    client: RospyDriver, after: float, accept: Callable[[dict[str, Any]], bool] = bool
) -> dict[str, Any]:
    """The first MoraiSimProcStatus that reports a command later than `after` (s of sim
    time; 0: any command) and that `accept`s, waiting generously."""
    since = 0
    for _ in range(600):
        received = client.messages(STATUS[0], since=since, count=1, timeout=60)
        since += len(received)
        for status in received:
            if status["latest_command_time"] > after and accept(status):
                return status
    raise AssertionError("no MoraiSimProcStatus reported the awaited state")


def at_end(status: dict[str, Any]) -> bool:
    return status["current_status"] == AT_END


def record_drive(
    egosim: Callable[..., Any],
    rospy_client: Callable[..., RospyDriver],
    bag: Path,
    duration: float = RECORD_S,
    accelerate_s: float = ACCELERATE_S,
) -> None:
    """`duration` s of the default scenario with a scripted controller, recorded by egosim:
    `accelerate_s` s of throttle, then the brake."""
    recording = egosim(
        "--clock", "sim", "--rtf", "0", "--duration", str(duration), "--record", str(bag)
    )
    driver = rospy_client(recording)
    # Accelerate while steering gently left, then brake: a curved drive that stops.
    driver.stream(*CTRL, {"longlCmdType": 1, "accel": 0.5, "front_steer": 0.03}, rate=50)
    driver.subscribe(*EGO)
    driver.messages(EGO[0], count=round(accelerate_s * EGO_RATE_HZ), timeout=60)
    driver.stream(*CTRL, {"longlCmdType": 1, "brake": 0.3, "front_steer": -0.02}, rate=50)
    assert recording.process.wait(120) == 0


def subscriber_connections(master_uri: str, topic: str) -> int:
    """How many subscribers /egosim's publisher of `topic` has live connections to (its
    Slave API's getBusInfo)."""
    _, _, node_uri = xmlrpc.client.ServerProxy(master_uri).lookupNode("/test", "/egosim")
    _, _, connections = xmlrpc.client.ServerProxy(node_uri).getBusInfo("/test")
    return sum(c[2] == "o" and c[4] == topic and c[5] for c in connections)


def replayed(client: RospyDriver, topic: str, since: int) -> list[dict[str, Any]]:
    return client.messages(topic, since=since, count=0, timeout=0)


def test_replayed_trajectories_match_the_recording(
    egosim: Callable[..., Any], rospy_client: Callable[..., RospyDriver], tmp_path: Path
) -> None:
    bag = tmp_path / "drive.bag"
    record_drive(egosim, rospy_client, bag)
    recording = Recording.of(bag)
    assert recording.duration_s == pytest.approx(RECORD_S, abs=0.1)
    recorded_ego_path = math.dist(recording.ego_rows[0][:2], recording.ego_rows[-1][:2])
    assert recorded_ego_path > 5.0, "the scripted controller should have moved the ego"

    player = egosim("--clock", "sim", "--rtf", "0")
    shutil.copy(bag, player.data_root / "drive.bag")
    client = rospy_client(player)
    for topic in (EGO, OBJECTS, STATUS):
        client.subscribe(*topic)
    client.messages(STATUS[0], count=1)
    commanded = 0.0

    for speed in (1, 4):
        for target in (TARGET_EGO, TARGET_NPC, TARGET_PEDESTRIAN):
            commanded = replay_and_compare(client, recording, speed, target, after=commanded)


def replay_and_compare(
    client: RospyDriver,
    recording: Recording,
    speed: int,
    target: int,
    after: float,
    bag_name: str = "drive.bag",
) -> float:
    """Play the whole bag for one target at one speed; compare what the simulator reports
    with the recording at matched times. The time (s) the play command arrived."""
    since = {topic: client.received(topic) for topic in (EGO[0], OBJECTS[0])}
    assert sim_proc(
        client,
        sim_process_status=PLAY,
        replay_option=LOAD | SET_TARGET | SET_SPEED,
        rosbag_file_name=bag_name,
        replay_target_option=target,
        replay_speed=speed,
    )
    end = status_after(client, after, at_end)
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
    ego_errors = [math.dist(xy(m["position"]), recording.ego_xy(t)) for t, m in egos]
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


def test_missing_corrupt_or_outside_bags_fail_to_load_and_the_simulation_goes_on(
    egosim: Callable[..., Any], rospy_client: Callable[..., RospyDriver], tmp_path: Path
) -> None:
    player = egosim("--clock", "sim", "--rtf", "0")
    (player.data_root / "corrupt.bag").write_bytes(b"#ROSBAG V2.0\n" + bytes(range(256)) * 8)
    (player.data_root / "notes.bag").write_text("not a bag at all\n")
    (tmp_path / "outside.bag").write_bytes(b"")
    client = rospy_client(player)
    client.subscribe(*STATUS)
    client.subscribe(*EGO)
    commanded = 0.0
    for name in ("missing.bag", "corrupt.bag", "notes.bag", "../outside.bag", "/etc/passwd"):
        loaded = sim_proc(
            client, sim_process_status=PLAY, replay_option=LOAD, rosbag_file_name=name
        )
        status = status_after(client, commanded)
        commanded = status["latest_command_time"]
        assert not loaded, name
        assert status["command_result"] == BAG_LOAD_FAILED, name
        assert status["current_mode"] == SIMULATION_MODE, name
        # Still simulating: the ego keeps being reported, later and later.
        first = client.next_message(EGO[0])["header"]["stamp"]
        assert client.next_message(EGO[0])["header"]["stamp"] > first
    assert player.process.popen.poll() is None


def test_replay_info_reports_the_recorded_inputs_and_objects(
    egosim: Callable[..., Any], rospy_client: Callable[..., RospyDriver], tmp_path: Path
) -> None:
    bag = tmp_path / "data" / "short.bag"
    record_drive(egosim, rospy_client, bag, duration=4.0, accelerate_s=0.4)
    recording = Recording.of(bag)
    player = egosim("--clock", "sim", "--rtf", "0")
    client = rospy_client(player)
    for topic in (STATUS, REPLAY_INFO):
        client.subscribe(*topic)
    assert sim_proc(
        client,
        sim_process_status=PLAY,
        replay_option=LOAD | SET_SPEED,
        rosbag_file_name="short.bag",
        replay_speed=2,
    )
    end = status_after(client, 0.0, at_end)
    commanded = end["latest_command_time"]
    infos = client.messages(REPLAY_INFO[0], count=0, timeout=0)
    # Nothing before the command: ReplayInfo is published during replay only.
    assert infos and min(m["header"]["stamp"] for m in infos) > commanded
    playing = [m for m in infos if m["header"]["stamp"] <= commanded + recording.duration_s / 2]
    assert len(playing) >= 10
    for info in playing:
        t = recording.start_ns + (info["header"]["stamp"] - commanded) * 2 * 1e9
        ego = recording.ego_at(t)
        assert info["ego_acc"] == pytest.approx(ego["accel"], abs=1e-9)
        assert info["ego_brake"] == pytest.approx(ego["brake"], abs=1e-9)
        assert info["ego_steer"] == pytest.approx(ego["front_steer"], abs=1e-6)
        q = info["orientation"]
        assert q["x"] == pytest.approx(0.0) and q["y"] == pytest.approx(0.0)
        yaw = math.degrees(2 * math.atan2(q["z"], q["w"]))
        assert math.remainder(yaw - ego["heading"], 360.0) == pytest.approx(0.0, abs=1e-6)
        # The yaw rate lies between the recorded heading's slopes just before and after t.
        slopes = [
            math.radians(
                recording.ego_at(t + d)["heading"] - recording.ego_at(t + d - 1e6)["heading"]
            )
            / 1e-3
            for d in (-1e6, 2e6)
        ]
        assert min(slopes) - 1e-6 <= info["angular_velocity"]["z"] <= max(slopes) + 1e-6
        for list_name, count in (
            ("npc_list", "num_of_npcs"),
            ("pedestrian_list", "num_of_pedestrian"),
            ("obstacle_list", "num_of_obstacle"),
        ):
            expected = recording.objects_at(t, list_name)
            shown = {o["unique_id"]: xy(o["position"]) for o in info[list_name]}
            assert info[count] == len(shown)
            assert shown.keys() == expected.keys()
            assert all(math.dist(shown[u], expected[u]) < TOLERANCE_M for u in expected)


def test_a_bag_recorded_by_rosbag_record_replays(
    egosim: Callable[..., Any],
    rospy_client: Callable[..., RospyDriver],
    spawn_ros: Callable[..., Any],
) -> None:
    simulator = egosim("--clock", "sim", "--rtf", "2")
    client = rospy_client(simulator)
    for topic in (EGO, OBJECTS, STATUS):
        client.subscribe(*topic)
    bag = simulator.data_root / "rosbag.bag"
    rosbag = spawn_ros(
        ["/usr/bin/rosbag", "record", "-O", str(bag), EGO[0], OBJECTS[0]],
        master_uri=simulator.master_uri,
        ROS_IP="127.0.0.1",
    )
    # rosbag's recorder prints nothing when it subscribes; its bag appears when it does,
    # and what it records begins once egosim's publishers have connected to it.
    active = bag.with_name(bag.name + ".active")
    deadline = time.monotonic() + EVENT_TIMEOUT_S
    while not active.exists():
        assert time.monotonic() < deadline, rosbag.stderr_text()
        time.sleep(0.05)
    for topic in (EGO[0], OBJECTS[0]):  # the client and rosbag
        until(
            lambda topic=topic: subscriber_connections(simulator.master_uri, topic) >= 2,
            f"egosim's {topic} to connect to the client and to rosbag record",
        )
    client.stream(*CTRL, {"longlCmdType": 1, "accel": 0.6, "front_steer": 0.04}, rate=50)
    client.messages(EGO[0], count=300, timeout=120)
    client.stop_stream(CTRL[0])
    rosbag.kill()  # SIGINT: rosbag closes the bag
    assert bag.exists()
    recording = Recording.of(bag)
    assert recording.duration_s > 2.0
    replay_and_compare(client, recording, 1, TARGET_EGO, after=0.0, bag_name="rosbag.bag")
