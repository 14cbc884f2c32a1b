"""MORAI's synchronous mode: the client steps the world, one step per tick, reproducibly."""

from __future__ import annotations

import itertools
import struct
import time
from pathlib import Path

import pytest

from tests import waiting

pytestmark = pytest.mark.ros

EGO = ("/Ego_topic", "morai_msgs/EgoVehicleStatus")
OBJECTS = ("/Object_topic", "morai_msgs/ObjectStatusList")
SYNC_CMD = ("/SyncModeCmd", "morai_msgs/MoraiSyncModeCmdSrv")
TICK = ("/SyncModeWaitForTick", "morai_msgs/MoraiWaitForTickSrv")
CTRL = ("/SyncModeCtrlCmd", "morai_msgs/MoraiSyncModeCtrlCmdSrv")
GEAR = ("/SyncModeSetGear", "morai_msgs/MoraiSyncModeSetGearSrv")
USER = "planner"
# /Ego_topic after every 10 ms step, so each tick publishes exactly one status.
EVERY_STEP = "rows:\n  ego_status: {rate_hz: 100}\n  object_status: {rate_hz: 100}\n"


def start_sync_mode(client, time_step_ms: int = 10) -> int:
    reply = client.call(
        *SYNC_CMD,
        {"request": {"user_id": USER, "start_sync_mode": True, "time_step": time_step_ms}},
    )["response"]
    assert reply["result"] is True
    assert reply["time_step"] == time_step_ms
    return reply["frame"]


def tick(client, frame: int, user_id: str = USER) -> dict:
    return client.call(*TICK, {"request": {"user_id": user_id, "frame": frame}})["response"]


def ctrl(client, frame: int, accel: float) -> bool:
    command = {"longlCmdType": 1, "accel": accel, "brake": 0.0}
    request = {"frame": frame, "command": command, "sensor_capture": False}
    return client.call(*CTRL, {"request": request})["response"]["result"]


@pytest.fixture
def network_file(tmp_path: Path) -> str:
    path = tmp_path / "network.yaml"
    path.write_text(EVERY_STEP)
    return str(path)


def test_each_tick_steps_the_world_exactly_once(egosim, rospy_client, network_file) -> None:
    client = rospy_client(egosim("--map", "straight", "--clock", "sync", "--network", network_file))
    client.subscribe(*EGO)
    client.wait_connected(EGO[0])
    first = start_sync_mode(client, time_step_ms=20)
    replies = [tick(client, first + k) for k in range(1, 11)]
    assert [r["frame"] for r in replies] == [first + k for k in range(1, 11)]
    assert all(r["tick_status"] and not r["pause_status"] for r in replies)
    assert [r["time"] for r in replies] == [f"{0.02 * k:.6f}" for k in range(1, 11)]
    statuses = client.messages(EGO[0], count=10)
    assert [round(m["header"]["stamp"], 9) for m in statuses] == [
        pytest.approx(0.02 * k) for k in range(1, 11)
    ]
    assert [r["vehicle_status"]["header"]["stamp"] for r in replies] == [
        m["header"]["stamp"] for m in statuses
    ]


def test_a_tick_to_a_later_frame_steps_once_per_frame(egosim, rospy_client, network_file) -> None:
    client = rospy_client(egosim("--map", "straight", "--clock", "sync", "--network", network_file))
    client.subscribe(*EGO)
    client.wait_connected(EGO[0])
    first = start_sync_mode(client)
    reply = tick(client, first + 5)
    assert (reply["frame"], reply["time"]) == (first + 5, "0.050000")
    assert len(client.messages(EGO[0], count=5)) == 5


def test_the_current_or_a_past_frame_ticks_once(egosim, rospy_client) -> None:
    client = rospy_client(egosim("--map", "straight", "--clock", "sync"))
    first = start_sync_mode(client)
    tick(client, first + 3)
    for k, frame in enumerate((first + 3, first + 1, 0), start=4):
        reply = tick(client, frame)
        assert reply["tick_status"] is True
        assert (reply["frame"], reply["time"]) == (first + k, f"{0.01 * k:.6f}")


def test_only_the_user_who_started_it_ticks(egosim, rospy_client) -> None:
    client = rospy_client(egosim("--map", "straight", "--clock", "sync"))
    first = start_sync_mode(client)
    assert tick(client, first + 1, user_id="intruder")["tick_status"] is False
    assert tick(client, first + 1)["tick_status"] is True


def test_ticks_need_sync_mode_started(egosim, rospy_client) -> None:
    client = rospy_client(egosim("--map", "straight", "--clock", "sync"))
    reply = tick(client, 1)
    assert (reply["tick_status"], reply["frame"], reply["time"]) == (False, 0, "0.000000")


def stop_sync_mode(client) -> None:
    request = {"request": {"user_id": USER, "start_sync_mode": False, "time_step": 0}}
    assert client.call(*SYNC_CMD, request)["response"]["result"] is True


def test_a_real_time_run_switches_into_sync_mode_and_back(egosim, rospy_client) -> None:
    client = rospy_client(egosim("--map", "straight"))
    first = start_sync_mode(client)
    held = float(tick(client, first + 1)["time"])
    time.sleep(0.5)  # the loop must not step a world the client owns
    assert float(tick(client, first + 2)["time"]) == pytest.approx(held + 0.01, abs=1e-9)
    assert ctrl(client, first + 3, 1.0) is True

    stop_sync_mode(client)
    time.sleep(0.5)  # back in real time, the world moves on its own
    again = start_sync_mode(client)
    assert again == first + 2
    assert float(tick(client, again + 1)["time"]) > held + 0.3


def test_stopping_sync_mode_started_with_clock_sync_lets_the_clock_run(
    egosim, rospy_client
) -> None:
    client = rospy_client(egosim("--map", "straight", "--clock", "sync"))
    client.subscribe("/clock", "rosgraph_msgs/Clock")
    client.wait_connected("/clock")
    first = start_sync_mode(client)
    tick(client, first + 10)
    stop_sync_mode(client)
    stamps = [m["clock"] for m in client.messages("/clock", count=30)]
    assert stamps[-1] > 0.1 + 0.05  # beyond the ticks: the loop steps the world again
    assert stamps == sorted(stamps)


def test_a_command_takes_effect_at_its_frame(egosim, rospy_client) -> None:
    client = rospy_client(egosim("--map", "straight", "--clock", "sync"))
    first = start_sync_mode(client)
    assert ctrl(client, first + 5, 1.0) is True
    assert tick(client, first + 4)["vehicle_status"]["velocity"]["x"] == 0.0
    moving = tick(client, first + 20)["vehicle_status"]
    assert moving["velocity"]["x"] > 0.0
    assert moving["accel"] == pytest.approx(1.0)
    # a frame already ticked: the command drives the next tick
    assert ctrl(client, first + 20, 0.0) is True
    assert tick(client, first + 21)["vehicle_status"]["accel"] == 0.0
    assert ctrl(client, first + 2, 0.5) is True
    assert tick(client, first + 22)["vehicle_status"]["accel"] == pytest.approx(0.5)


def test_set_gear_at_a_frame(egosim, rospy_client) -> None:
    client = rospy_client(egosim("--map", "straight", "--clock", "sync"))
    first = start_sync_mode(client)
    reverse = {"request": {"gear": 2, "frame": first + 1}}
    assert client.call(*GEAR, reverse)["response"]["result"] is True
    assert ctrl(client, first + 1, 1.0) is True
    backwards = tick(client, first + 30)["vehicle_status"]
    assert backwards["velocity"]["x"] < 0.0
    bad = {"request": {"gear": 9, "frame": first + 31}}
    assert client.call(*GEAR, bad)["response"]["result"] is False


def drive_and_record(egosim, rospy_client, network_file) -> dict[str, list[str]]:
    client = rospy_client(egosim("--clock", "sync", "--network", network_file))
    for topic, type_name in (EGO, OBJECTS):
        client.subscribe(topic, type_name, raw=True)
        client.wait_connected(topic)
    first = start_sync_mode(client)
    for k in range(1, 151):
        if k % 30 == 1:
            assert ctrl(client, first + k, 0.2 + k / 500.0) is True
        assert tick(client, first + k)["tick_status"] is True
    return {
        topic: [m["hex"] for m in client.messages(topic, count=150)]
        for topic in (EGO[0], OBJECTS[0])
    }


def test_two_runs_of_the_same_calls_publish_the_same_bytes(
    egosim, rospy_client, network_file
) -> None:
    first = drive_and_record(egosim, rospy_client, network_file)
    second = drive_and_record(egosim, rospy_client, network_file)
    for topic in (EGO[0], OBJECTS[0]):
        assert len(first[topic]) == 150
        assert first[topic] == second[topic]
    assert len(set(first[EGO[0]])) == 150  # the ego moved and time went on


ADD = ("/SyncModeAddObject", "morai_msgs/MoraiSyncModeAddObjectSrv")
REMOVE = ("/SyncModeRemoveObject", "morai_msgs/MoraiSyncModeRemoveObjectSrv")
LOAD = ("/SyncModeScenarioLoad", "morai_msgs/MoraiSyncModeSLSrv")


def obstacles_after_tick(client, frame: int) -> list[dict]:
    since = client.received(OBJECTS[0])
    tick(client, frame)
    return client.messages(OBJECTS[0], since=since, count=1)[0]["obstacle_list"]


def test_objects_come_and_go_at_their_frames(egosim, rospy_client, network_file) -> None:
    client = rospy_client(egosim("--map", "straight", "--clock", "sync", "--network", network_file))
    client.subscribe(*OBJECTS)
    client.wait_connected(OBJECTS[0])
    first = start_sync_mode(client)
    cone = {"name": "Cone", "position": {"x": 10.0, "y": -1.75, "z": 0.0}, "heading": 90.0}
    assert client.call(*ADD, {"request": {**cone, "frame": first + 2}})["response"]["result"]
    unknown = {**cone, "name": "Flying_Saucer", "frame": first + 1}  # applied at once
    assert client.call(*ADD, {"request": unknown})["response"]["result"] is False
    assert obstacles_after_tick(client, first + 1) == []
    (added,) = obstacles_after_tick(client, first + 2)
    assert (added["name"], added["heading"]) == ("Cone", pytest.approx(90.0))
    assert (added["position"]["x"], added["position"]["y"]) == (10.0, -1.75)
    remove = {"unique_id": added["unique_id"], "frame": first + 3}
    assert client.call(*REMOVE, {"request": remove})["response"]["result"] is True
    assert obstacles_after_tick(client, first + 3) == []
    again = {"unique_id": added["unique_id"], "frame": first + 4}
    assert client.call(*REMOVE, {"request": again})["response"]["result"] is False


def test_scenario_load_at_a_frame(egosim, rospy_client, network_file) -> None:
    simulator = egosim("--map", "straight", "--clock", "sync", "--network", network_file)
    (simulator.data_root / "barrier.yaml").write_text(
        "map: straight\nobstacles:\n  - {model: Barrier, pose: {x: 30.0, y: -1.75}}\n"
    )
    client = rospy_client(simulator)
    client.subscribe(*OBJECTS)
    client.wait_connected(OBJECTS[0])
    first = start_sync_mode(client)
    load = {"frame": first + 1, "file_name": "barrier", "load_obstacle_data": True}
    assert client.call(*LOAD, {"request": load})["response"]["result"] is True
    assert [o["name"] for o in obstacles_after_tick(client, first + 1)] == ["Barrier"]
    missing = {**load, "frame": first + 2, "file_name": "no_such_scenario"}
    assert client.call(*LOAD, {"request": missing})["response"]["result"] is False


# MORAI's own clients, as they call the services (morai_example's 2021.08
# synchronous_mode.py and its later frame-0 variant, MORAI-EDU's RL chapter): a frame
# that never advances, and one tick per call.
EVENT = ("/Service_MoraiEventCmd", "morai_msgs/MoraiEventCmdSrv")
THROTTLE = {"longlCmdType": 1, "accel": 0.6, "brake": 0.0}
NEUTRAL, DRIVE = 3, 4


def speeds_and_frames(replies: list[dict]) -> tuple[list[float], list[int]]:
    return (
        [r["vehicle_status"]["velocity"]["x"] for r in replies],
        [r["frame"] for r in replies],
    )


def test_the_2021_08_example_loop_ticks_once_per_call(egosim, rospy_client) -> None:
    """SyncModeCmd without a time_step (20 ms), then WaitForTick with the start's frame
    every time, the ego's CtrlCmd inside it."""
    client = rospy_client(egosim("--map", "straight"), profile="2021.08")
    start = {"user_id": "sync_master", "start_sync_mode": True}
    started = client.call(*SYNC_CMD, {"request": start})["response"]
    assert started["result"] is True
    request = {"user_id": started["user_id"], "frame": started["frame"], "command": THROTTLE}
    replies = [client.call(*TICK, {"request": request})["response"] for _ in range(50)]
    speeds, frames = speeds_and_frames(replies)
    assert all(r["tick_status"] for r in replies)
    assert frames == [started["frame"] + k for k in range(1, 51)]
    assert replies[0]["vehicle_status"]["accel"] == pytest.approx(0.6)  # in that very tick
    assert speeds == sorted(speeds) and speeds[-1] > 1.0
    stamps = [r["vehicle_status"]["header"]["stamp"] for r in replies]
    assert [b - a for a, b in itertools.pairwise(stamps)] == [pytest.approx(0.02, abs=1e-6)] * 49


def test_the_frame_0_variant_ticks_once_per_call(egosim, rospy_client) -> None:
    """SyncModeCtrlCmd for the frame the client counts, WaitForTick(frame = 0)."""
    client = rospy_client(egosim("--map", "straight"))
    next_frame = start_sync_mode(client, time_step_ms=20) + 1
    assert tick(client, next_frame)["frame"] == next_frame
    replies = []
    for _ in range(50):
        next_frame += 1
        assert ctrl(client, next_frame, THROTTLE["accel"]) is True
        replies.append(tick(client, 0))
    speeds, frames = speeds_and_frames(replies)
    assert frames == list(range(next_frame - 49, next_frame + 1))
    times = [float(r["time"]) for r in replies]
    assert [b - a for a, b in itertools.pairwise(times)] == [pytest.approx(0.02, abs=1e-9)] * 49
    assert speeds == sorted(speeds) and speeds[-1] > 1.0


def test_the_rl_chapter_loop_drives_with_the_frames_it_is_answered(egosim, rospy_client) -> None:
    """SetGear and WaitForTick for the start's frame, then per step: WaitForTick, a
    SyncModeCtrlCmd for the frame it answered, WaitForTick again; reset by stop and
    start."""
    client = rospy_client(egosim("--map", "straight"))
    neutral = {"request": {"option": 2, "ctrl_mode": 3, "gear": NEUTRAL}}
    assert client.call(*EVENT, neutral)["response"]["gear"] == NEUTRAL
    for episode in range(2):
        frame = start_sync_mode(client, time_step_ms=20)
        gear = {"request": {"gear": DRIVE, "frame": frame}}
        assert client.call(*GEAR, gear)["response"]["result"] is True
        assert tick(client, frame)["frame"] == frame + 1
        replies = []
        for _ in range(20):
            answered = tick(client, frame)["frame"]
            assert ctrl(client, answered, THROTTLE["accel"]) is True
            replies.append(tick(client, frame))
        speeds, frames = speeds_and_frames(replies)
        assert frames == [frame + 1 + 2 * k for k in range(1, 21)], episode
        assert speeds == sorted(speeds) and speeds[-1] > 0.5, episode
        stop_sync_mode(client)


EGO_EVERY_TICK = "rows:\n  ego_status: {rate_hz: 50}\n"  # one status per 20 ms tick


def raw_stamp_ns(message: dict) -> int:
    """header.stamp of a serialized EgoVehicleStatus (seq, then secs and nsecs)."""
    secs, nsecs = struct.unpack_from("<II", bytes.fromhex(message["hex"]), 4)
    return secs * 1_000_000_000 + nsecs


def test_a_real_time_run_stamps_sync_ticks_with_the_world_time(
    egosim, rospy_client, tmp_path: Path
) -> None:
    network = tmp_path / "ego_every_tick.yaml"
    network.write_text(EGO_EVERY_TICK)
    client = rospy_client(egosim("--map", "straight", "--network", str(network)))
    client.subscribe(*EGO, raw=True)
    client.wait_connected(EGO[0])
    first = start_sync_mode(client, time_step_ms=20)
    replies = [tick(client, first + k) for k in range(1, 6)]
    replied = [r["vehicle_status"]["header"]["stamp"] for r in replies]

    def sync_stamps() -> list[int] | None:
        stamps = [raw_stamp_ns(m) for m in client.messages(EGO[0], count=0, timeout=0)]
        ticked = [s for s in stamps if any(abs(s / 1e9 - r) < 1e-6 for r in replied)]
        return ticked if len(ticked) == 5 else None

    ticked = waiting.until(sync_stamps, "the five ticks' /Ego_topic messages")
    assert [b - a for a, b in itertools.pairwise(ticked)] == [20_000_000] * 4

    # 2 s of the world in one call, ahead of the wall clock; after the stop real time
    # goes on from there
    tick(client, first + 105)
    stop_sync_mode(client)
    burst_end = ticked[-1] + 2_000_000_000

    def real_time_after_the_burst() -> list[int] | None:
        # the burst's own messages may still be arriving as the stop returns
        stamps = [raw_stamp_ns(m) for m in client.messages(EGO[0], count=0, timeout=0)]
        return stamps if sum(s > burst_end for s in stamps) >= 20 else None

    stamps = waiting.until(
        real_time_after_the_burst, "20 real-time /Ego_topic messages after the 2 s sync call"
    )
    assert stamps == sorted(stamps)
