"""A command holds until the next one, as in a simulator that reads the latest value each
frame; MORAI's own example client (longlCmdType left at 0) drives; a dead-man timeout is
an opt-in network setting."""

from __future__ import annotations

from typing import Any

import pytest

pytestmark = pytest.mark.ros

EGO = ("/Ego_topic", "morai_msgs/EgoVehicleStatus")
CTRL = ("/ctrl_cmd", "morai_msgs/CtrlCmd")


def _speeds_for(client: Any, seconds: float) -> list[float]:
    """Ego speeds (km/h) over the next `seconds` of simulation time."""
    since = client.received(EGO[0])
    first = None
    speeds: list[float] = []
    while True:
        received = client.messages(EGO[0], since=since, count=1)
        assert received, "no /Ego_topic within 20 s"
        since += len(received)
        for message in received:
            stamp = message["header"]["stamp"]
            first = stamp if first is None else first
            speeds.append(message["velocity"]["x"] * 3.6)
            if stamp - first >= seconds:
                return speeds


def test_one_latched_velocity_command_keeps_driving(egosim, rospy_client) -> None:
    client = rospy_client(egosim("--map", "straight", "--clock", "sim", "--rtf", "4"))
    client.subscribe(*EGO)
    client.publish(*CTRL, {"longlCmdType": 2, "velocity": 30.0}, latch=True)
    speeds = _speeds_for(client, 12.0)
    assert speeds[-1] == pytest.approx(30.0, abs=1.0)
    assert min(speeds[len(speeds) // 2 :]) > 25.0


def test_morai_example_command_with_unset_mode_drives(egosim, rospy_client) -> None:
    """MORAI's driving example builds CtrlCmd(accel, brake, steering): longlCmdType 0."""
    simulator = egosim("--map", "straight", "--clock", "sim", "--rtf", "4")
    client = rospy_client(simulator)
    client.subscribe(*EGO)
    client.stream(*CTRL, {"accel": 0.5, "brake": 0.0, "front_steer": 0.0}, rate=20)
    speeds = _speeds_for(client, 3.0)
    client.stop_stream(CTRL[0])
    assert speeds[-1] > 5.0
    assert "unknown longitudinal mode" not in simulator.process.stderr_text()


def test_the_dead_man_timeout_brakes_after_silence_when_set(egosim, rospy_client, tmp_path) -> None:
    network = tmp_path / "network.yaml"
    network.write_text("command_timeout_s: 0.5\n")
    timed = egosim("--map", "straight", "--clock", "sim", "--rtf", "4", "--network", str(network))
    client = rospy_client(timed)
    client.subscribe(*EGO)
    client.publish(*CTRL, {"longlCmdType": 2, "velocity": 30.0}, latch=True)
    speeds = _speeds_for(client, 6.0)
    assert max(speeds) < 15.0
    assert speeds[-1] == pytest.approx(0.0, abs=0.01)


def test_one_sync_mode_command_holds_through_every_later_tick(egosim, rospy_client) -> None:
    client = rospy_client(egosim("--map", "straight", "--clock", "sync"))
    started = client.call(
        "/SyncModeCmd",
        "morai_msgs/MoraiSyncModeCmdSrv",
        {"request": {"user_id": "planner", "start_sync_mode": True, "time_step": 10}},
    )["response"]
    frame = started["frame"] + 1
    command = {"longlCmdType": 1, "accel": 0.5, "brake": 0.0}
    request = {"frame": frame, "command": command, "sensor_capture": False}
    control = ("/SyncModeCtrlCmd", "morai_msgs/MoraiSyncModeCtrlCmdSrv")
    assert client.call(*control, {"request": request})["response"]["result"]
    # 5 s of ticks, 100 per call, with no further command.
    statuses = []
    for k in range(1, 6):
        reply = client.call(
            "/SyncModeWaitForTick",
            "morai_msgs/MoraiWaitForTickSrv",
            {"request": {"user_id": "planner", "frame": frame + 100 * k}},
        )["response"]
        statuses.append(reply["vehicle_status"])
    assert all(s["accel"] == pytest.approx(0.5) and s["brake"] == 0.0 for s in statuses)
    speeds = [s["velocity"]["x"] for s in statuses]
    assert speeds == sorted(speeds)
    assert speeds[-1] > 5.0
