"""The drive log: what the evaluation's rules find, on the console as it begins."""

from __future__ import annotations

import logging

import pytest

from egosim.app.drive_log import DriveLog, drive_log
from egosim.bridge import BridgeContext, simulation_context
from egosim.world import World
from egosim.world.map import build_builtin_map
from egosim.world.scenario import parse_scenario
from egosim.world.signals import RED
from egosim.world.vehicle import Pose

DT = 0.01
TOWN = build_builtin_map("town")
LANE = TOWN.lanes["R1_E_1"]  # ends at light TL2_W
LOGGER = "egosim.drive"


def run_along(context: BridgeContext, s0: float, speed: float, seconds: float) -> None:
    """Hold the main ego on R1_E_1 at `speed` from `s0`, a tick of the log per step."""
    world = context.world
    start = world.sim_time
    for _ in range(round(seconds / DT)):
        x, y, _, heading = TOWN.pose_at(LANE.id, s0 + speed * (world.sim_time - start))
        world.egos[0].vehicle.teleport(Pose(x=x, y=y, yaw=heading), speed)
        context.tick(DT)


def hold_before_the_line(context: BridgeContext, run_up: float, speed: float) -> None:
    """Place the main ego `run_up` m before R1_E_1's stop line, held at `speed`."""
    assert LANE.stop_line_s is not None
    vehicle = context.world.egos[0].vehicle
    x, y, _, heading = TOWN.pose_at(LANE.id, LANE.stop_line_s - run_up)
    vehicle.teleport(Pose(x=x, y=y, yaw=heading), speed)
    vehicle.hold_speed(speed)


def town_context(**scenario: object) -> BridgeContext:
    """The town (with `scenario`'s egos and obstacles, if any), its drive log a stage."""
    world = World(TOWN, parse_scenario({"map": "town", **scenario}) if scenario else None)
    context = simulation_context(world)
    context.pipeline = DriveLog().on(context.pipeline)
    return context


def speed_in(message: str, label: str) -> float:
    """The speed a line ends with, after `label` (m/s)."""
    head, _, tail = message.rpartition(f", {label} ")
    assert head and tail.endswith(" m/s"), message
    return float(tail.removesuffix(" m/s"))


def messages(caplog: pytest.LogCaptureFixture, level: int) -> list[str]:
    return [r.getMessage() for r in caplog.records if r.name == LOGGER and r.levelno == level]


def test_a_red_light_run_is_logged_where_and_when_it_happened(
    caplog: pytest.LogCaptureFixture,
) -> None:
    context = town_context()
    assert LANE.traffic_light_ids and LANE.stop_line_s is not None
    context.world.signals.set_light(LANE.traffic_light_ids[0], RED)
    caplog.set_level(logging.DEBUG, LOGGER)
    run_along(context, LANE.stop_line_s - 20.0, 10.0, 3.0)
    x, y, _, _ = TOWN.pose_at(LANE.id, LANE.stop_line_s)
    (red,) = messages(caplog, logging.INFO)
    assert red.startswith(
        f"ego 1: red light run: light {LANE.traffic_light_ids[0]} red at the stop line of lane "
        f"R1_E_1 at ({x:.1f}, {y:.1f}) m, t 2.0"
    ), red
    assert speed_in(red, "ego at") == pytest.approx(10.0, abs=0.15)  # one step's coasting


@pytest.mark.parametrize("tick_s", [0.2, 0.5, 1.0])
def test_a_red_light_run_between_coarse_sync_ticks_is_logged(
    caplog: pytest.LogCaptureFixture, tick_s: float
) -> None:
    # At 30 m/s a sync tick carries the ego 6 to 30 m on: farther than a placed ego jumps.
    context = town_context()
    assert LANE.traffic_light_ids and LANE.stop_line_s is not None
    context.world.signals.set_light(LANE.traffic_light_ids[0], RED)
    caplog.set_level(logging.DEBUG, LOGGER)
    speed, run_up = 30.0, 40.0
    hold_before_the_line(context, run_up, speed)
    for _ in range(round(3.0 / tick_s)):
        context.tick(tick_s)
    (red,) = messages(caplog, logging.INFO)
    assert red.startswith(
        f"ego 1: red light run: light {LANE.traffic_light_ids[0]} red at the stop line of lane "
        f"R1_E_1 at "
    ), red
    when = float(red.rpartition(", t ")[2].partition(" s")[0])
    assert when == pytest.approx(run_up / speed, abs=0.02)
    assert speed_in(red, "ego at") == pytest.approx(speed, abs=0.5)


def test_a_red_light_run_in_the_very_first_sync_tick_is_logged(
    caplog: pytest.LogCaptureFixture,
) -> None:
    # The ego's first sample is the world before the first step, so a crossing inside
    # that step has a before and an after.
    context = town_context()
    assert LANE.traffic_light_ids and LANE.stop_line_s is not None
    context.world.signals.set_light(LANE.traffic_light_ids[0], RED)
    caplog.set_level(logging.DEBUG, LOGGER)
    speed, run_up, tick_s = 30.0, 20.0, 1.0
    hold_before_the_line(context, run_up, speed)
    context.tick(tick_s)
    (red,) = messages(caplog, logging.INFO)
    assert red.startswith(f"ego 1: red light run: light {LANE.traffic_light_ids[0]} red"), red
    when = float(red.rpartition(", t ")[2].partition(" s")[0])
    assert when == pytest.approx(run_up / speed, abs=0.02)


def test_a_lane_departure_is_only_a_debug_line(caplog: pytest.LogCaptureFixture) -> None:
    context = town_context()
    caplog.set_level(logging.DEBUG, LOGGER)
    world = context.world
    x, y, _, heading = TOWN.pose_at(LANE.id, 20.0)
    for k in range(100):  # drifting left across the lane's edge, 1 m/s sideways
        world.egos[0].vehicle.teleport(Pose(x=x + 0.1 * k, y=y + 0.01 * k, yaw=heading), 10.0)
        context.tick(DT)
    assert messages(caplog, logging.INFO) == []
    (departure,) = messages(caplog, logging.DEBUG)
    assert departure.startswith("ego 1: lane departure: over the edge of lane R1_E_1")


def test_a_teleport_over_a_stop_line_is_no_red_light_run(caplog: pytest.LogCaptureFixture) -> None:
    context = town_context()
    assert LANE.traffic_light_ids and LANE.stop_line_s is not None
    context.world.signals.set_light(LANE.traffic_light_ids[0], RED)
    caplog.set_level(logging.DEBUG, LOGGER)
    run_along(context, LANE.stop_line_s - 2.0, 0.0, 0.5)
    # Placed on the junction lane past the line, as a scenario load or a replay seek does.
    x, y, _, heading = TOWN.pose_at("J2_W_E_straight_1", 3.0)
    context.world.egos[0].vehicle.teleport(Pose(x=x, y=y, yaw=heading), 0.0)
    for _ in range(10):
        context.tick(DT)
    assert messages(caplog, logging.INFO) == []


def test_a_collision_names_the_ego_what_it_hit_and_the_impact_speed(
    caplog: pytest.LogCaptureFixture,
) -> None:
    barrier_x, barrier_y, _, _ = TOWN.pose_at(LANE.id, 60.0)
    context = town_context(
        ego={"start": {"lane": LANE.id, "s": 30.0}},
        obstacles=[{"model": "Barrier", "pose": {"x": barrier_x, "y": barrier_y}}],
    )
    caplog.set_level(logging.INFO, LOGGER)
    run_along(context, 30.0, 8.0, 4.0)
    (collision,) = messages(caplog, logging.INFO)
    assert collision.startswith(
        f"ego 1: collision (obstacle) with Barrier (id 2) at ({barrier_x:.1f}, {barrier_y:.1f}) m"
    ), collision
    assert speed_in(collision, "impact at") == pytest.approx(8.0, abs=0.15)


def test_no_stage_when_its_lines_would_not_be_shown() -> None:
    logger = logging.getLogger(LOGGER)
    before = logger.level
    try:
        logger.setLevel(logging.WARNING)
        assert drive_log() is None
        logger.setLevel(logging.INFO)
        console_log = drive_log()
        assert console_log is not None
        names = console_log.on(simulation_context(World(TOWN)).pipeline).names
        assert names.index("drive log start") + 1 == names.index("world")
        assert names.index("drive log") == names.index("world") + 1
    finally:
        logger.setLevel(before)
