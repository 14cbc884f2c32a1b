"""The OpenSCENARIO gallery of examples/openscenario/: each file loads, runs with the
ego in auto mode (the scenario drives it) and does what its comment says; the
distribution files give the cases they state."""

from __future__ import annotations

from pathlib import Path

import pytest

from egosim.batch.suite import scenario_suite
from egosim.maps import load_map, scenario_map_location
from egosim.scenario_files import read_scenario_file
from egosim.world import World
from egosim.world.openscenario import ScenarioRun
from egosim.world.scenario import ScenarioLoadOptions
from egosim.world.vehicle import ControlCommand, LongitudinalMode

GALLERY = Path(__file__).parents[1] / "examples" / "openscenario"
DT = 0.01


def gallery_run(name: str, drives_ego: bool = True) -> tuple[World, ScenarioRun]:
    path = GALLERY / name
    scenario = read_scenario_file(path)
    world = World(load_map(scenario_map_location(scenario.map_reference, path.parent)))
    world.load_scenario(scenario, ScenarioLoadOptions(scenario_drives_ego=drives_ego))
    run = world.storyboard
    assert isinstance(run, ScenarioRun)
    return world, run


def tick(world: World, run: ScenarioRun, drives_ego: bool = True) -> None:
    run.step(DT, drives_ego)
    world.step(DT)


def test_every_gallery_file_says_what_it_checks() -> None:
    for path in GALLERY.glob("*.xosc"):
        text = path.read_text("utf-8")
        assert "<!--" in text.split("<OpenSCENARIO>")[0], path.name
        if "ParameterValueDistribution" not in text:
            assert "Checks: " in text, path.name


def test_cut_in() -> None:
    world, run = gallery_run("cut_in.xosc")
    rt = run.rt
    ego, car = rt.entity("Ego"), rt.entity("CutIn")
    started = ended = headway_time = None
    while not run.finished:
        tick(world, run)
        change = rt.elements[("action", "LaneChange")]
        if started is None and change.state == "runningState":
            started = rt.time - DT
        if ended is None and change.state == "completeState":
            ended = rt.time - DT
            assert car.y == pytest.approx(ego.y, abs=1e-9)  # the ego's lane centre
        if headway_time is None and rt.variables["closeGapSeen"] is True:
            headway_time = rt.time - DT
            gap = (car.box_centre()[0] - car.definition.length / 2) - (
                ego.box_centre()[0] + ego.definition.length / 2
            )
            assert gap / ego.speed == pytest.approx(1.2, abs=0.02 * DT * 20)
    assert started is not None and ended is not None
    assert ended - started == pytest.approx(3.0, abs=DT + 1e-9)
    assert car.speed == pytest.approx(18.0)
    assert headway_time is not None and headway_time > ended
    assert run.outcome().state == "stopped"


def test_braking_target() -> None:
    # A stand-in for the stack: it follows the target's speed, slower when close.
    world, run = gallery_run("braking_target.xosc", drives_ego=False)
    ego, target = run.rt.entity("Ego"), run.rt.entity("Target")
    vehicle = world.egos[0].vehicle
    began = stood = None
    x_began = travelled = 0.0
    while not run.finished:
        gap = target.box_centre()[0] - ego.box_centre()[0] - 4.5
        speed = max(target.speed - (2.0 if gap < 8.0 else 0.0), 0.0)
        vehicle.command(ControlCommand(mode=LongitudinalMode.VELOCITY, velocity=speed))
        tick(world, run, drives_ego=False)
        if began is None and target.speed < 50 / 3.6 - 1e-9:
            began, x_began = run.rt.time - DT, target.x
        if stood is None and began is not None and target.speed == 0.0:
            stood, travelled = run.rt.time, target.x - x_began
    assert began is not None and stood is not None
    assert began == pytest.approx(2.0, abs=DT + 1e-9)
    assert stood - began == pytest.approx((50 / 3.6) / 4.0, abs=2 * DT)
    assert travelled == pytest.approx((50 / 3.6) ** 2 / (2 * 4.0), abs=0.2)
    assert run.outcome().verdict == "success"
    assert not world.ego_collision_log


def test_braking_target_run_into_fails_the_evaluation() -> None:
    # In auto mode the scenario drives the ego on at 50 km/h into the stopping target.
    world, run = gallery_run("braking_target.xosc")
    while not run.finished:
        tick(world, run)
    assert run.outcome().verdict == "failure"
    assert world.ego_collision_log


def test_pedestrian_crossing() -> None:
    world, run = gallery_run("pedestrian_crossing.xosc")
    rt = run.rt
    ego, walker = rt.entity("Ego"), rt.entity("Walker")
    walked_at: list[float] = []
    met = None
    while not run.finished:
        tick(world, run)
        if walker.y > -4.75 and not walked_at:
            walked_at.append(walker.speed)
        if met is None and ego.collisions:
            met = (ego.x + 3.5, walker.y)  # the front bumper the scenario times the walk for
    assert walked_at == [pytest.approx(1.5, abs=1e-6)]  # steady over the last 3 m
    # They meet at the crossing line, the walker a step short of the lane centre.
    assert met is not None
    assert met[0] == pytest.approx(150.0, abs=0.5)
    assert met[1] == pytest.approx(-1.75, abs=1.0)
    assert run.outcome().verdict == "failure"
    # A RelativeObjectPosition from the ego's start: 160 m ahead, 3.5 m to its left.
    assert (rt.entity("Barrier").x, rt.entity("Barrier").y) == pytest.approx((210.0, 1.75))


def test_braking_target_sweep() -> None:
    cases = scenario_suite(GALLERY / "braking_target_sweep.xosc", "true", 20.0, "sim")
    assert [c.name for c in cases] == [
        f"braking_target_sweep[TestSpeed_kph={v},Deceleration={d}]"
        for v in (30, 40, 50)
        for d in (2, 6)
    ]
    assert cases[0].openscenario.endswith("braking_target.xosc")


def test_braking_target_random() -> None:
    cases = scenario_suite(GALLERY / "braking_target_random.xosc", "true", 20.0, "sim")
    again = scenario_suite(GALLERY / "braking_target_random.xosc", "true", 20.0, "sim")
    assert len(cases) == 8 and [c.name for c in cases] == [c.name for c in again]
    for case in cases:
        assert 8 <= float(case.scenario_parameters["Headway"]) <= 20
        assert 1 <= float(case.scenario_parameters["Deceleration"]) <= 9
