"""The ego drives on the lane's surface: its height and grade."""

import math

import numpy as np
import pytest

from egosim.world import World
from egosim.world.map import Lane, LaneMap
from egosim.world.map.builtin_origin import BUILTIN_GEOREF
from egosim.world.scenario import parse_scenario

GRADE = 0.1


def _ramp() -> LaneMap:
    """One 200 m lane east along a 10 % climb, and its twin coming down."""
    x = np.linspace(0.0, 200.0, 21)
    up = np.column_stack((x, np.full_like(x, -1.75), GRADE * x))
    down = np.column_stack((x[::-1], np.full_like(x, 1.75), GRADE * x[::-1]))
    lanes = [Lane("up", up, np.full(21, 3.5), 20.0), Lane("down", down, np.full(21, 3.5), 20.0)]
    return LaneMap("ramp", lanes, [], [], [], [], BUILTIN_GEOREF)


@pytest.mark.parametrize(("lane", "pitch"), [("up", -math.atan(GRADE)), ("down", math.atan(GRADE))])
def test_ego_takes_the_height_and_pitch_of_the_lane_under_it(lane: str, pitch: float) -> None:
    scenario = parse_scenario({"map": "ramp", "ego": {"start": {"lane": lane, "s": 50.0}}}, "ramp")
    world = World(_ramp(), scenario)
    world.step()
    pose = world.ego_status().pose
    assert pose.z == pytest.approx(GRADE * pose.x, abs=1e-6)
    assert pose.pitch == pytest.approx(pitch, abs=1e-9)
