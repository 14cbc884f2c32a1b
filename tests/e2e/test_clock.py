"""--clock sim: /clock drives a use_sim_time node's time, and headers carry that time."""

from __future__ import annotations

import itertools
import time

import pytest

pytestmark = pytest.mark.ros

EGO = ("/Ego_topic", "morai_msgs/EgoVehicleStatus")
CLOCK = ("/clock", "rosgraph_msgs/Clock")
PHYSICS_DT_S = 0.01


def test_sim_time_runs_faster_than_wall_time_at_rtf_0(egosim, rospy_client) -> None:
    client = rospy_client(egosim("--map", "straight", "--clock", "sim", "--rtf", "0"))
    assert client.request("get_param", name="/use_sim_time") is True
    client.subscribe(*CLOCK)
    client.next_message(CLOCK[0])
    sim_start, wall_start = client.now(), time.monotonic()
    client.messages(CLOCK[0], count=2000, timeout=60.0)
    sim_elapsed, wall_elapsed = client.now() - sim_start, time.monotonic() - wall_start
    assert sim_elapsed > wall_elapsed > 0.0


def test_header_stamps_are_clock_times(egosim, rospy_client) -> None:
    client = rospy_client(egosim("--map", "straight", "--clock", "sim", "--rtf", "2"))
    client.subscribe(*CLOCK)
    client.subscribe(*EGO)
    client.next_message(EGO[0])
    egos = client.messages(EGO[0], count=20)[-20:]
    clocks = {round(m["clock"], 9) for m in client.messages(CLOCK[0], count=0, timeout=0)}
    stamps = [round(m["header"]["stamp"], 9) for m in egos]
    assert set(stamps) <= clocks
    # Every stamp is a whole number of physics steps, 20 ms apart at the 50 Hz default.
    steps = [s / PHYSICS_DT_S for s in stamps]
    assert steps == pytest.approx([round(s) for s in steps], abs=1e-6)
    assert [b - a for a, b in itertools.pairwise(stamps)] == pytest.approx([0.02] * 19, abs=1e-9)
