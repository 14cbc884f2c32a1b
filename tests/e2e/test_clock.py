"""--clock sim: /clock drives a use_sim_time node's time, and headers carry that time."""

from __future__ import annotations

import itertools
import time

import pytest

from egosim.msgs import get_profile
from egosim.ros1 import Node
from tests.ros1.helpers import wait_until

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


def test_header_stamps_are_clock_times(egosim) -> None:
    # A listener on egosim's own transport: it keeps every message, where rospy's
    # use_sim_time subscription to /clock keeps only the latest one.
    simulator = egosim("--map", "straight", "--clock", "sim", "--rtf", "0")
    profile = get_profile("26.r1")
    received: dict[str, list[float]] = {CLOCK[0]: [], EGO[0]: []}
    stamp_of = {CLOCK[0]: lambda m: m.clock, EGO[0]: lambda m: m.header.stamp}

    def listen(topic: str, type_name: str) -> None:
        message_type = profile.message(type_name)

        def keep(data: bytes, header: object) -> None:
            stamp = stamp_of[topic](message_type.deserialize(data))
            received[topic].append(stamp.sec + stamp.nanosec * 1e-9)

        node.subscribe(topic, message_type, keep)

    with Node("stamp_listener", master_uri=simulator.master_uri, rosout_logger=None) as node:
        listen(*CLOCK)
        listen(*EGO)
        wait_until(lambda: len(received[EGO[0]]) >= 50)
        wait_until(
            lambda: bool(received[CLOCK[0]]) and received[CLOCK[0]][-1] >= received[EGO[0]][49]
        )
    clocks = {round(t, 9) for t in received[CLOCK[0]]}
    stamps = [round(t, 9) for t in received[EGO[0]][:50]]
    # The subscriptions connect at different moments: compare from the first /clock on.
    assert {s for s in stamps if s >= min(clocks)} <= clocks
    assert max(stamps) >= min(clocks)
    # Every stamp is a whole number of physics steps, 20 ms apart at the 50 Hz default.
    steps = [s / PHYSICS_DT_S for s in stamps]
    assert steps == pytest.approx([round(s) for s in steps], abs=1e-6)
    assert [b - a for a, b in itertools.pairwise(stamps)] == pytest.approx([0.02] * 49, abs=1e-9)
