"""Stop lines crossed at any speed and any sample rate: a case samples its ego after every
step, 10 ms at the batch's physics rate and up to 1 s when a sync client sets the tick, and
a car at 60 m/s covers 60 m in that second (more than the 5.5 m between the town's stop
lines and their junctions, more than a whole junction lane). Each crossing is recorded
once, at the closed-form time the ego reaches the line."""

from __future__ import annotations

import dataclasses

import pytest

from egosim.evaluation import DriveEvaluator, InfractionKind
from egosim.maps import load_map
from egosim.world import World
from egosim.world.map import LaneMap, build_builtin_map
from egosim.world.scenario import parse_scenario
from egosim.world.signals import GREEN, RED, YELLOW
from tests.evaluation.drives import along_lanes, sample_exactly

SPEEDS_MPS = (5.0, 10.0, 20.0, 30.0, 45.0, 60.0)
SAMPLE_PERIODS_S = (0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1.0)
"""The batch's physics step, and sync ticks up to the longest a client may ask (1000 ms)."""
CROSSING_S = 1.337
"""When the line is reached: between two samples at every rate but the finest."""


@dataclasses.dataclass(frozen=True)
class Approach:
    """A signalised lane, the junction lane straight on and the lane after it."""

    map_name: str
    lanes: tuple[str, str, str]

    def lane_map(self) -> LaneMap:
        return MAPS[self.map_name]

    @property
    def light(self) -> str:
        (light,) = self.lane_map().lanes[self.lanes[0]].traffic_light_ids
        return light

    @property
    def line_s(self) -> float:
        """The stop line's station: the town's 5.5 m before its junction, the MGeo
        sample's at the lane's end, where the junction lane begins."""
        lane = self.lane_map().lanes[self.lanes[0]]
        return lane.length if lane.stop_line_s is None else lane.stop_line_s


MAPS = {"town": build_builtin_map("town"), "mgeo_sample": load_map("mgeo_sample")}
TOWN = Approach("town", ("R1_E_1", "J2_W_E_straight_1", "R2_E_1"))
MGEO = Approach("mgeo_sample", ("R3_E_1", "J1_W_E_straight_1", "R1_E_1"))


def through(
    approach: Approach, aspect: int, speed: float, period: float, run_up: float | None = None
) -> tuple[DriveEvaluator, float]:
    """Drive straight through the junction at `speed` under a light held at `aspect`,
    sampled every `period`, reaching the line after `run_up` m (default: at CROSSING_S);
    the evaluator and the time the line is reached."""
    world = World(approach.lane_map())
    world.signals.set_light(approach.light, aspect)
    evaluator = DriveEvaluator(world)
    run_up = speed * CROSSING_S if run_up is None else run_up
    crossing_s = run_up / speed
    script = along_lanes(world, approach.lanes, approach.line_s - run_up, speed)
    sample_exactly(world, evaluator, script, crossing_s + 2.0 * period, period)
    return evaluator, crossing_s


@pytest.mark.parametrize("period", SAMPLE_PERIODS_S)
@pytest.mark.parametrize("speed", SPEEDS_MPS)
@pytest.mark.parametrize("approach", [TOWN, MGEO], ids=lambda a: a.map_name)
def test_a_red_light_run_is_recorded_at_the_time_the_line_is_reached(
    approach: Approach, speed: float, period: float
) -> None:
    evaluator, crossing_s = through(approach, RED, speed, period)
    (run,) = evaluator.infractions()
    assert run.kind is InfractionKind.RED_LIGHT
    assert run.time_s == pytest.approx(crossing_s, abs=1e-6)
    x, y, _, _ = approach.lane_map().pose_at(approach.lanes[0], approach.line_s)
    assert (run.x, run.y) == pytest.approx((x, y))
    assert approach.light in run.detail
    assert evaluator.score().metrics["driving_score"] == pytest.approx(0.70)


@pytest.mark.parametrize("aspect", [GREEN, YELLOW])
@pytest.mark.parametrize("approach", [TOWN, MGEO], ids=lambda a: a.map_name)
def test_a_light_that_lets_traffic_go_is_no_infraction_at_any_rate(
    approach: Approach, aspect: int
) -> None:
    for speed in (SPEEDS_MPS[0], SPEEDS_MPS[-1]):
        for period in (SAMPLE_PERIODS_S[0], SAMPLE_PERIODS_S[-1]):
            evaluator, _ = through(approach, aspect, speed, period)
            assert evaluator.infractions() == [], (speed, period)


def test_a_sample_before_the_line_and_the_next_past_the_junction() -> None:
    # 3 m before the line, then 57 m on: the 5.5 m to the junction, its 28 m lane, and
    # 23.5 m into the lane after it; no sample lies on the lane the line is on past it.
    evaluator, crossing_s = through(TOWN, RED, 60.0, 1.0, run_up=3.0)
    (run,) = evaluator.infractions()
    assert (run.kind, run.time_s) == (InfractionKind.RED_LIGHT, pytest.approx(crossing_s))


def test_a_red_light_run_while_turning_left_between_sparse_samples() -> None:
    town = MAPS["town"]
    world = World(town)
    world.signals.set_light("TL2_W", RED)
    evaluator = DriveEvaluator(world)
    lanes = ("R1_E_1", "J2_W_N_left_1", "R16_N_1")
    speed, run_up = 15.0, 7.0
    script = along_lanes(world, lanes, TOWN.line_s - run_up, speed)
    sample_exactly(world, evaluator, script, 3.0, 1.0)  # 15 m arcs through the turn
    (run,) = evaluator.infractions()
    assert (run.kind, run.time_s) == (InfractionKind.RED_LIGHT, pytest.approx(run_up / speed))


def test_changing_lanes_across_a_red_stop_line() -> None:
    # From the left lane 2 m before the line to the right lane 3 m past it, in one sample.
    town = MAPS["town"]
    world = World(town)
    world.signals.set_light("TL2_W", RED)
    evaluator = DriveEvaluator(world)
    left = town.pose_at("R1_E_1", TOWN.line_s - 2.0)
    right = town.pose_at("R1_E_2", TOWN.line_s + 3.0)

    def script(t: float) -> tuple[float, float, float, float]:
        if t < 0.5:
            return left[0], left[1], left[3], 10.0
        return right[0], right[1], right[3], 10.0

    sample_exactly(world, evaluator, script, 1.0, 0.5)
    (run,) = evaluator.infractions()
    assert run.kind is InfractionKind.RED_LIGHT
    assert "lane R1_E_2" in run.detail  # the lane it crossed the line in
    assert run.time_s == pytest.approx(0.5 * 2.0 / 5.0)


def test_the_light_as_it_shows_when_the_line_is_reached() -> None:
    """The program of the town's junction 2 starts in TL2_W's yellow (3 s), then all red:
    a car reaching the line in the yellow is fine, one reaching it after is not."""
    signals = {"intersections": [{"id": 2, "initial_phase": 4}]}
    scenario = parse_scenario(
        {"map": "town", "ego": {"start": {"lane": "R1_E_1", "s": 10.0}}, "signals": signals}
    )
    outcomes = []
    for crossing_s in (2.5, 3.5):
        world = World(MAPS["town"], scenario)
        evaluator = DriveEvaluator(world)
        speed = 10.0
        script = along_lanes(world, TOWN.lanes, TOWN.line_s - speed * crossing_s, speed)
        sample_exactly(world, evaluator, script, crossing_s + 0.5, 0.01)
        outcomes.append([(i.kind, round(i.time_s, 6)) for i in evaluator.infractions()])
    assert outcomes == [[], [(InfractionKind.RED_LIGHT, 3.5)]]


def stop_sign_map() -> LaneMap:
    """The straight map with a stop line (no light) 30 m along R1_E_1."""
    base = build_builtin_map("straight")
    lanes = [
        dataclasses.replace(lane, stop_line_s=30.0) if lane.id == "R1_E_1" else lane
        for lane in base.lanes.values()
    ]
    return LaneMap("signs", lanes, [], [], [], [], base.georef)


@pytest.mark.parametrize("period", [0.01, 0.2, 1.0])
@pytest.mark.parametrize("speed", [5.0, 30.0, 60.0])
def test_a_stop_sign_run_at_speed_between_samples(speed: float, period: float) -> None:
    world = World(stop_sign_map())
    evaluator = DriveEvaluator(world)
    crossing_s = 0.337  # the line 30 m along the lane
    script = along_lanes(world, ("R1_E_1",), 30.0 - speed * crossing_s, speed)
    sample_exactly(world, evaluator, script, crossing_s + 2.0 * period, period)
    (run,) = evaluator.infractions()
    assert run.kind is InfractionKind.STOP_LINE
    assert run.time_s == pytest.approx(crossing_s, abs=1e-6)


def test_standing_at_a_stop_sign_then_going_between_sparse_samples() -> None:
    world = World(stop_sign_map())
    evaluator = DriveEvaluator(world)

    def script(t: float) -> tuple[float, float, float, float]:
        s, speed = (27.0, 0.0) if t < 2.0 else (27.0 + 20.0 * (t - 2.0), 20.0)
        x, y, _, heading = world.map.pose_at("R1_E_1", s)
        return x, y, heading, speed

    sample_exactly(world, evaluator, script, 4.0, 1.0)
    assert evaluator.infractions() == []
