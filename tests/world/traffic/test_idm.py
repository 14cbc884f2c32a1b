"""The IDM against its closed forms, alone and driving NPCs."""

import math

import numpy as np
import pytest
from tests.world.traffic.scenes import run, world_from

from egosim.world import World
from egosim.world.traffic import IntelligentDriverModel

IDM = IntelligentDriverModel()
# The loop map is a ring of two lanes (R1_N_1 -> R2_S_1 -> R1_N_1) whose curves allow
# 11.2 m/s, so desired speeds below that hold all the way round.
LOOP_EGO_OUT_OF_THE_WAY = {"start": {"lane": "R1_N_2", "s": 0.0}}


def test_acceleration_is_zero_at_the_equilibrium_gap() -> None:
    for v, v0 in ((5.0, 20.0), (10.0, 20.0), (15.0, 16.0)):
        gap = (IDM.min_gap_m + v * IDM.time_headway_s) / math.sqrt(1.0 - (v / v0) ** 4)
        assert IDM.equilibrium_gap(v, v0) == pytest.approx(gap)
        a = IDM.acceleration(np.array([v]), np.array([v0]), np.array([gap]), np.array([0.0]))
        assert a[0] == pytest.approx(0.0, abs=1e-12)


def test_free_road_acceleration_is_the_free_term() -> None:
    v = np.array([0.0, 10.0, 20.0])
    a = IDM.acceleration(v, np.full(3, 20.0), np.full(3, np.inf), np.zeros(3))
    np.testing.assert_allclose(a, IDM.max_accel_mps2 * (1.0 - (v / 20.0) ** 4))


def test_npc_on_a_free_road_converges_to_its_desired_speed() -> None:
    world = world_from(
        {
            "map": "loop",
            "ego": LOOP_EGO_OUT_OF_THE_WAY,
            "npcs": [{"start": {"lane": "R1_N_1", "s": 0.0}, "target_speed_mps": 8.0}],
        }
    )
    run(world, 60.0)
    assert world.npcs.speed[0] == pytest.approx(8.0, abs=1e-6)


def _path_gap(world: World, leader: int, follower: int) -> float:
    """Bumper-to-bumper distance along the ring from follower to leader, m."""
    npcs = world.npcs
    ahead = npcs.s[leader] - npcs.s[follower]
    if npcs.lane[leader] != npcs.lane[follower]:
        ahead += world.map.lane_lengths[npcs.lane[follower]]
    return float(ahead - (npcs.dims[leader, 0] + npcs.dims[follower, 0]) / 2.0)


def test_follower_settles_at_the_equilibrium_gap() -> None:
    leader_v0, follower_v0 = 6.0, 10.0
    world = world_from(
        {
            "map": "loop",
            "ego": LOOP_EGO_OUT_OF_THE_WAY,
            "npcs": [
                {"start": {"lane": "R1_N_1", "s": 60.0}, "target_speed_mps": leader_v0},
                {"start": {"lane": "R1_N_1", "s": 20.0}, "target_speed_mps": follower_v0},
            ],
        }
    )
    run(world, 120.0)
    # The leader in turn follows the follower round the ring, 400 m behind, which holds
    # it a hair under its v0: the equilibrium is the one at the speed they share.
    shared_speed = float(world.npcs.speed[0])
    assert shared_speed == pytest.approx(leader_v0, abs=1e-2)
    assert world.npcs.speed[1] == pytest.approx(shared_speed, abs=1e-6)
    assert _path_gap(world, 0, 1) == pytest.approx(
        IDM.equilibrium_gap(shared_speed, follower_v0), abs=1e-3
    )
