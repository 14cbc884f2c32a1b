"""OpenSCENARIO through the bridge: ScenarioLoad names an .xosc (with or without its
extension) inside the data roots, the tick pipeline's storyboard stage runs it, and in
control mode auto the scenario drives the ego."""

from __future__ import annotations

import logging
import shutil
from pathlib import Path

import pytest

from egosim.bridge import simulation_context
from egosim.bridge.protocol.codes import ControlMode
from egosim.bridge.scene.scenarios import on_scenario_load, prepare_scenario
from egosim.maps import load_map
from egosim.msgs import get_profile
from egosim.world import World

PROFILE = get_profile("26.r1")
GALLERY = Path(__file__).parents[2] / "examples" / "openscenario"


def read_in_thread(context, name: str, vehicles: bool = True):  # type: ignore[no-untyped-def]
    """prepare_scenario as the transport runs it, every kind of object asked for."""
    request = PROFILE.message("morai_msgs/ScenarioLoad").new(
        file_name=name,
        delete_all=True,
        load_ego_vehicle_data=True,
        load_surrounding_vehicle_data=vehicles,
        load_pedestrian_data=True,
        load_obstacle_data=True,
    )
    return prepare_scenario(context, context.row("scenario_load"), request)


@pytest.fixture
def roots(tmp_path: Path) -> Path:
    for name in ("cut_in.xosc", "highway.xodr", "braking_target.xosc"):
        shutil.copy(GALLERY / name, tmp_path / name)
    shutil.copytree(GALLERY / "catalogs", tmp_path / "catalogs")
    return tmp_path


def loaded(roots: Path, name: str, mode: ControlMode = ControlMode.EXTERNAL):  # type: ignore[no-untyped-def]
    world = World(load_map(str(roots / "highway.xodr")))
    context = simulation_context(world, data_roots=(roots,))
    context.ego_session(world.egos[0]).set_ctrl_mode(mode, by="the test")
    prepared = read_in_thread(context, name)
    assert prepared.scenario is not None, prepared.error
    on_scenario_load(context, context.row("scenario_load"), prepared)
    return world, context


def test_scenario_load_of_an_xosc_by_name_places_its_entities(roots: Path) -> None:
    world, context = loaded(roots, "cut_in")
    assert "storyboard" in context.pipeline.names
    assert context.pipeline.names.index("storyboard") < context.pipeline.names.index("world")
    ego = world.ego_status()
    assert (ego.pose.x, ego.pose.y) == pytest.approx((50.0, -1.75))
    assert ego.velocity[0] == pytest.approx(20.0)  # Init's SpeedAction
    assert "2015_Kia_K5" in world.objects().names


def test_the_load_flags_choose_the_kinds_of_entities(roots: Path) -> None:
    world = World(load_map(str(roots / "highway.xodr")))
    context = simulation_context(world, data_roots=(roots,))
    on_scenario_load(
        context, context.row("scenario_load"), read_in_thread(context, "cut_in", False)
    )
    assert "2015_Kia_K5" not in world.objects().names


def test_in_external_mode_the_stack_drives_the_ego_and_the_others_follow_the_scenario(
    roots: Path, caplog: pytest.LogCaptureFixture
) -> None:
    world, context = loaded(roots, "cut_in.xosc")
    run = world.storyboard
    assert run is not None
    with caplog.at_level(logging.WARNING):
        for _ in range(100):
            context.tick(0.01)
    car = run.rt.entity("CutIn")  # type: ignore[attr-defined]
    assert car.x == pytest.approx(30.0 + 25.0, abs=1e-6)
    # Nobody commands the ego: it holds its Init speed (a velocity command) in its lane.
    assert world.ego_status().pose.x == pytest.approx(70.0, abs=0.5)


def test_in_auto_mode_the_scenario_drives_the_ego(roots: Path) -> None:
    world, context = loaded(roots, "braking_target.xosc", ControlMode.AUTO)
    run = world.storyboard
    assert run is not None
    while not run.finished:
        context.tick(0.01)
    assert run.outcome().verdict == "failure"  # it drove into the braking target
    assert world.egos[0].unique_id in world.scripted_egos


def test_an_xosc_outside_the_roots_or_with_a_mistake_is_refused(
    roots: Path, tmp_path: Path
) -> None:
    (roots / "broken.xosc").write_text("<OpenSCENARIO><FileHeader revMajor='1'", encoding="utf-8")
    world = World(load_map(str(roots / "highway.xodr")))
    context = simulation_context(world, data_roots=(roots,))
    prepared = read_in_thread(context, "broken.xosc")
    assert prepared.scenario is None and "broken.xosc:1" in prepared.error
    prepared = read_in_thread(context, "../elsewhere.xosc")
    assert prepared.scenario is None and "outside the data roots" in prepared.error
