"""Scoring against closed-form drives: each infraction at the time and place it must be."""

from __future__ import annotations

import dataclasses
import math

import pytest

from egosim.evaluation import (
    METRIC_NAMES,
    CriterionError,
    DriveEvaluator,
    EvaluationSettings,
    InfractionKind,
    Route,
    parse_criterion,
)
from egosim.evaluation.comfort import comfort_figures
from egosim.world import World
from egosim.world.map import LaneMap, build_builtin_map
from egosim.world.scenario import parse_scenario
from egosim.world.signals import GREEN, RED
from egosim.world.vehicle import DEFAULT_EGO_MODEL, ego_model
from tests.evaluation.drives import DT, along_lane, drive, sample_exactly, straight

EGO = ego_model(DEFAULT_EGO_MODEL)
LANE_Y = -1.75  # the straight map's R1_E_1 centreline, heading east
LANE_WIDTH = 3.5


def straight_world(obstacles: list[dict] | None = None) -> World:
    scenario = parse_scenario(
        {
            "map": "straight",
            "ego": {"start": {"lane": "R1_E_1", "s": 0.0}},
            "obstacles": obstacles or [],
        }
    )
    return World(build_builtin_map("straight"), scenario)


def front_ahead_of_pose(world: World) -> float:
    """How far the main ego's front bumper is ahead of its pose's point, m."""
    status = world.ego_status()
    x, _ = world.egos[0].box_centre(status)
    return x - status.pose.x + EGO.length / 2.0  # heading east


def kinds(evaluator: DriveEvaluator, **kwargs: bool) -> list[InfractionKind]:
    return [i.kind for i in evaluator.infractions(**kwargs)]


def test_collision_with_a_static_object_at_the_time_it_must_happen() -> None:
    speed, obstacle_x = 10.0, 50.0
    cone = {"model": "Cone", "pose": {"x": obstacle_x, "y": LANE_Y}}
    world = straight_world([cone])
    front = front_ahead_of_pose(world)
    evaluator = DriveEvaluator(world)
    drive(world, evaluator, straight(0.0, LANE_Y, speed), 6.0)

    # The ego's front bumper reaches the cone's near face.
    expected_t = (obstacle_x - 0.4 / 2.0 - front) / speed
    score = evaluator.score()
    (collision,) = score.infractions
    assert collision.kind is InfractionKind.COLLISION_STATIC
    assert collision.time_s == pytest.approx(expected_t, abs=DT + 1e-9)
    assert (collision.x, collision.y) == pytest.approx((obstacle_x, LANE_Y))
    assert collision.magnitude == pytest.approx(speed, rel=0.01)  # the speed it hit at
    assert score.metrics["collisions"] == 1
    assert score.metrics["driving_score"] == pytest.approx(0.65)
    assert score.metrics["min_ttc_s"] == pytest.approx(0.0, abs=speed * DT)


def test_time_to_collision_and_headway_to_the_object_ahead() -> None:
    speed = 10.0
    world = straight_world([{"model": "Cone", "pose": {"x": 80.0, "y": LANE_Y}}])
    front = front_ahead_of_pose(world)
    evaluator = DriveEvaluator(world, settings=EvaluationSettings(safety_period_s=DT))
    drive(world, evaluator, straight(0.0, LANE_Y, speed), 2.0)

    gap_at_end = 80.0 - 0.2 - front - speed * 2.0
    # The speed a step leaves (coasting for one step from the held speed).
    speed_at_end = world.ego_status().speed
    metrics = evaluator.score().metrics
    # The cone stands still: the closing speed is the ego's speed.
    assert metrics["min_ttc_s"] == pytest.approx(gap_at_end / speed_at_end, abs=0.001)
    assert metrics["min_headway_s"] == pytest.approx(gap_at_end / speed_at_end, abs=0.001)


@pytest.mark.parametrize(("aspect", "expected"), [(RED, [InfractionKind.RED_LIGHT]), (GREEN, [])])
def test_running_a_red_light_at_its_stop_line(aspect: int, expected: list) -> None:
    town = build_builtin_map("town")
    lane = town.lanes["R1_E_1"]
    (light,) = lane.traffic_light_ids
    assert lane.stop_line_s is not None
    world = World(town)
    world.signals.set_light(light, aspect)
    evaluator = DriveEvaluator(world)
    s0, speed = lane.stop_line_s - 20.0, 10.0
    drive(world, evaluator, along_lane(world, lane.id, s0, speed), 3.0)

    assert kinds(evaluator) == expected
    if expected:
        (red,) = evaluator.infractions()
        assert red.time_s == pytest.approx(2.0, abs=DT + 1e-9)
        x, y, _, _ = town.pose_at(lane.id, lane.stop_line_s)
        assert (red.x, red.y) == pytest.approx((x, y))
        assert evaluator.score().metrics["driving_score"] == pytest.approx(0.70)


def stop_sign_world() -> World:
    """The straight map with a stop line (no light) 30 m along R1_E_1."""
    base = build_builtin_map("straight")
    lanes = [
        dataclasses.replace(lane, stop_line_s=30.0) if lane.id == "R1_E_1" else lane
        for lane in base.lanes.values()
    ]
    return World(LaneMap("signs", lanes, [], [], [], [], base.georef))


def test_a_stop_sign_run_without_stopping_is_a_stop_line_violation() -> None:
    world = stop_sign_world()
    evaluator = DriveEvaluator(world)
    drive(world, evaluator, straight(10.0, LANE_Y, 10.0), 3.0)
    (violation,) = evaluator.infractions()
    assert violation.kind is InfractionKind.STOP_LINE
    assert violation.time_s == pytest.approx(2.0, abs=DT + 1e-9)
    assert (violation.x, violation.y) == pytest.approx((30.0, LANE_Y))
    assert evaluator.score().metrics["driving_score"] == pytest.approx(0.80)


def test_stopping_at_a_stop_sign_then_going_is_no_violation() -> None:
    world = stop_sign_world()
    evaluator = DriveEvaluator(world)
    drive(world, evaluator, straight(28.0, LANE_Y, 0.0), 1.0)  # stand 2 m before the line
    drive(world, evaluator, straight(28.0 - 10.0, LANE_Y, 10.0), 1.0)
    assert kinds(evaluator) == []


def test_a_lane_departure_of_known_size() -> None:
    offset = 1.2  # to the left, still nearest to its own lane
    world = straight_world()
    evaluator = DriveEvaluator(world)
    drive(world, evaluator, straight(0.0, LANE_Y, 5.0), 1.0)
    drive(world, evaluator, straight(5.0 - 5.0 * 1.0, LANE_Y + offset, 5.0), 1.0)
    drive(world, evaluator, straight(10.0 - 5.0 * 2.0, LANE_Y, 5.0), 1.0)

    (departure,) = evaluator.infractions()
    assert departure.kind is InfractionKind.LANE_DEPARTURE
    assert departure.time_s == pytest.approx(1.0, abs=DT + 1e-9)
    assert departure.magnitude == pytest.approx(offset + EGO.width / 2.0 - LANE_WIDTH / 2.0)
    metrics = evaluator.score().metrics
    assert metrics["max_lateral_error_m"] == pytest.approx(offset)
    # One third of the samples at `offset`, the rest on the centreline.
    assert metrics["rms_lateral_error_m"] == pytest.approx(offset / math.sqrt(3.0), rel=0.01)
    assert metrics["driving_score"] == 1.0  # leaving the lane costs nothing by default


def test_driving_off_the_road_and_the_wrong_way() -> None:
    world = straight_world()
    evaluator = DriveEvaluator(world)
    drive(world, evaluator, straight(0.0, -9.0, 5.0), 1.0)  # 2 m beyond R1_E_2's edge
    drive(world, evaluator, straight(10.0, 1.75, 5.0), 2.0)  # eastwards in R1_W_1

    found = evaluator.infractions()
    # Out of its lane the whole time: one lane departure, as large as it got.
    assert [i.kind for i in found] == [
        InfractionKind.LANE_DEPARTURE,
        InfractionKind.OFF_ROAD,
        InfractionKind.WRONG_WAY,
    ]
    departure, off_road, wrong_way = found
    assert departure.magnitude == pytest.approx(9.0 - 5.25 + EGO.width / 2.0 - LANE_WIDTH / 2.0)
    assert off_road.magnitude == pytest.approx(9.0 - 5.25 - LANE_WIDTH / 2.0)
    assert wrong_way.time_s == pytest.approx(1.0, abs=DT + 1e-9)
    assert wrong_way.magnitude == pytest.approx(2.0, abs=2 * DT)


def test_a_route_half_driven_then_time_out() -> None:
    world = straight_world()
    route = Route([(0.0, LANE_Y), (100.0, LANE_Y)])
    evaluator = DriveEvaluator(world, route)
    drive(world, evaluator, straight(0.0, LANE_Y, 10.0), 5.0)
    drive(world, evaluator, straight(50.0 + 10.0 * 0.0, LANE_Y, 0.0), 1.0)

    rear_to_route = 0.0  # the route is followed by the ego's reference point
    score = evaluator.score(timed_out=True)
    assert score.metrics["route_completion"] == pytest.approx(0.5 + rear_to_route, abs=0.002)
    assert [i.kind for i in score.infractions] == [InfractionKind.TIMEOUT]
    assert score.metrics["driving_score"] == pytest.approx(0.5, abs=0.002)
    assert not evaluator.finished


def test_a_completed_route_finishes_the_drive_and_scores_full() -> None:
    world = straight_world()
    evaluator = DriveEvaluator(world, Route([(0.0, LANE_Y), (20.0, LANE_Y)]))
    drive(world, evaluator, straight(0.0, LANE_Y, 10.0), 2.0)
    assert evaluator.finished
    score = evaluator.score(timed_out=True)
    assert score.metrics["route_completion"] == 1.0
    assert score.metrics["driving_score"] == 1.0
    assert score.infractions == ()


@pytest.mark.parametrize("period", [0.01, 0.5, 1.0])
def test_a_route_is_followed_at_any_sample_rate(period: float) -> None:
    # At 40 m/s a 1 s sync tick moves the ego 40 m between samples.
    world = straight_world()
    evaluator = DriveEvaluator(world, Route([(float(x), LANE_Y) for x in range(201)]))
    sample_exactly(world, evaluator, straight(0.0, LANE_Y, 40.0), 4.0, period)
    assert evaluator.score().metrics["route_completion"] == pytest.approx(0.8)
    sample_exactly(world, evaluator, straight(0.0, LANE_Y, 40.0), 1.0, period)
    assert evaluator.finish_reason == "route_completed"


def test_standing_still_too_long_is_blocked_and_ends_the_drive() -> None:
    world = straight_world()
    evaluator = DriveEvaluator(world, settings=EvaluationSettings(blocked_after_s=2.0))
    drive(world, evaluator, straight(0.0, LANE_Y, 0.0), 3.0)
    (blocked,) = evaluator.infractions()
    assert blocked.kind is InfractionKind.BLOCKED
    assert blocked.time_s == pytest.approx(2.0 + DT, abs=DT + 1e-9)
    assert evaluator.finished


def test_penalty_coefficients_are_configurable() -> None:
    world = straight_world([{"model": "Cone", "pose": {"x": 20.0, "y": LANE_Y}}])
    penalties = {InfractionKind.COLLISION_STATIC: 0.9}
    evaluator = DriveEvaluator(world, settings=EvaluationSettings(penalties=penalties))
    drive(world, evaluator, straight(0.0, LANE_Y, 10.0), 3.0)
    assert evaluator.score().metrics["driving_score"] == pytest.approx(0.9)


def test_comfort_figures_of_a_sinusoidal_acceleration() -> None:
    amplitude, omega = 2.0, 2.0 * math.pi * 0.5
    times = [k * 0.001 for k in range(20001)]  # 20 s, ten whole periods
    lateral = [amplitude * math.sin(omega * t) for t in times]
    figures = comfort_figures(times, [0.0] * len(times), lateral)
    assert figures["max_lat_accel_mps2"] == pytest.approx(amplitude, rel=1e-4)
    assert figures["rms_lat_accel_mps2"] == pytest.approx(amplitude / math.sqrt(2.0), rel=1e-3)
    assert figures["max_lat_jerk_mps3"] == pytest.approx(amplitude * omega, rel=1e-3)
    assert figures["rms_lat_jerk_mps3"] == pytest.approx(amplitude * omega / math.sqrt(2), rel=1e-3)
    assert figures["max_long_accel_mps2"] == 0.0


def test_criteria_read_and_check() -> None:
    metrics = {"route_completion": 0.96, "collisions": 0, "min_ttc_s": None, "red_light_count": 1}
    assert parse_criterion("route_completion >= 0.95", METRIC_NAMES).check(metrics).passed
    assert parse_criterion("no_collision", METRIC_NAMES).check(metrics).passed
    assert parse_criterion("min_ttc_s >= 1.5", METRIC_NAMES).check(metrics).passed
    failed = parse_criterion("no_red_light", METRIC_NAMES).check(metrics)
    assert not failed.passed and failed.value == 1
    for bad in ("route_completion >> 1", "no_such_thing", "speediness <= 3"):
        with pytest.raises(CriterionError):
            parse_criterion(bad, METRIC_NAMES)


def test_a_route_through_lanes_and_its_first_metres() -> None:
    route = Route.through_lanes(build_builtin_map("straight"), ["R1_E_1"])
    assert route.length == pytest.approx(1000.0)
    first = route.first(40.0)
    assert first.length == pytest.approx(40.0)
    assert first.points[-1] == pytest.approx((40.0, LANE_Y))
    world = straight_world()
    evaluator = DriveEvaluator(world, first)
    drive(world, evaluator, straight(0.0, LANE_Y, 10.0), 1.0)
    assert evaluator.score().metrics["route_completion"] == pytest.approx(0.25, abs=0.003)
