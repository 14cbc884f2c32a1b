"""`egosim run` options a user picks: a map file, the default protocol release."""

from __future__ import annotations

from pathlib import Path

import pytest

from egosim.msgs import get_profile
from tests.e2e.probe import handshake

pytestmark = pytest.mark.ros

MAPS = Path(__file__).parents[1] / "data" / "maps"


def test_runs_on_an_opendrive_map(egosim, rospy_client) -> None:
    client = rospy_client(egosim("--map", str(MAPS / "junction.xodr")))
    spec = client.call(
        "/Service_MoraiMapSpec", "morai_msgs/MoraiMapSpecSrv", {"request": {"load_map_data": True}}
    )["response"]
    assert spec["central_meridian"] == pytest.approx(127.0)
    assert spec["scale_factor"] == pytest.approx(1.0)
    client.subscribe("/Ego_topic", "morai_msgs/EgoVehicleStatus")
    status = client.next_message("/Ego_topic")
    assert status["distance_left_lane_boundary"] > 0.0


@pytest.mark.parametrize("release", ["26.r1", "24.r2", "2021.08"])
def test_protocol_option_sets_the_release_for_any_md5(egosim, release: str) -> None:
    simulator = egosim("--map", "straight", "--protocol", release)
    reply = handshake(simulator.master_uri, "/Ego_topic", "morai_msgs/EgoVehicleStatus", "*")
    expected = get_profile(release).message("morai_msgs/EgoVehicleStatus")
    assert reply["md5sum"] == expected.md5sum
    assert reply["message_definition"] == expected.definition
