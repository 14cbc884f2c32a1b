"""`egosim run --scenario FILE` runs the scenario's own map; an explicit --map must match it."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from egosim.app.options import RunOptions
from egosim.app.runner import StartupError, build_world
from egosim.maps import SHIPPED_MAPS_DIR, load_map
from egosim.world import World
from egosim.world.scenario import parse_scenario
from tests import morai_scenarios as morai
from tests.conftest import free_port
from tests.world.openscenario import stories

JUNCTION_XODR = Path(__file__).parents[1] / "data" / "maps" / "junction.xodr"


def scenario_file(folder: Path, map_field: str) -> Path:
    path = folder / "scenario.yaml"
    path.write_text(f"map: {map_field}\n")
    return path


def test_scenario_alone_runs_its_built_in_map(tmp_path: Path) -> None:
    world = build_world(RunOptions(scenario=scenario_file(tmp_path, "straight")))
    assert world.map.name == "straight"


def test_scenario_alone_runs_a_map_path_relative_to_the_file(tmp_path: Path) -> None:
    (tmp_path / "maps").mkdir()
    shutil.copy(JUNCTION_XODR, tmp_path / "maps" / "junction.xodr")
    folder = tmp_path / "scenarios"
    folder.mkdir()
    world = build_world(RunOptions(scenario=scenario_file(folder, "../maps/junction.xodr")))
    assert world.map.name == "junction"
    assert len(world.map.intersections) >= 1


def test_a_morai_scenario_runs_the_mgeo_folder_its_map_info_names(tmp_path: Path) -> None:
    # MORAI names maps as R_KR_PG_K-City; the MGeo folder of that name sits beside the file.
    shutil.copytree(SHIPPED_MAPS_DIR / "mgeo_sample", tmp_path / "R_KR_PG_Sample")
    document = morai.scenario("R_KR_PG_Sample", morai.ego(morai.on_link("R3_E_1", 0.5)))
    path = morai.write(tmp_path, "morai_scen.json", document)
    world = build_world(RunOptions(scenario=path))
    assert world.map.name == "R_KR_PG_Sample"
    assert world.ego_lane_state().lane_id == "R3_E_1"
    with pytest.raises(StartupError) as caught:
        build_world(RunOptions(map="town", scenario=path))
    assert str(caught.value).startswith(
        f"{path}: mapInfo.mapName: the scenario is for map 'R_KR_PG_Sample', --map gives 'town'"
    )


def test_an_openscenario_file_runs_the_mgeo_folder_its_road_network_names(
    tmp_path: Path,
) -> None:
    shutil.copytree(SHIPPED_MAPS_DIR / "mgeo_sample", tmp_path / "maps" / "sample")
    text = stories.scenario(
        stories.vehicle("Ego"),
        stories.teleport("Ego", '<LanePosition roadId="R3_E_1" laneId="-1" s="30"/>'),
    ).replace('filepath="highway.xodr"', 'filepath="maps/sample"')
    path = tmp_path / "on_mgeo.xosc"
    path.write_text(text, encoding="utf-8")
    world = build_world(RunOptions(scenario=path))
    assert world.map.name == "sample"
    lane = world.ego_lane_state()
    assert (lane.lane_id, lane.s) == ("R3_E_1", pytest.approx(30.0, abs=0.01))


def test_scenario_alone_runs_the_shipped_mgeo_sample(tmp_path: Path) -> None:
    world = build_world(RunOptions(scenario=scenario_file(tmp_path, "mgeo_sample")))
    assert world.map.name == "mgeo_sample"


def test_explicit_map_of_the_same_name_wins(tmp_path: Path) -> None:
    # A user's own copy of the map the scenario names: --map says where it is.
    copy = tmp_path / "elsewhere" / "junction.xodr"
    copy.parent.mkdir()
    shutil.copy(JUNCTION_XODR, copy)
    scenario = scenario_file(tmp_path, "junction.xodr")  # no such file next to it
    world = build_world(RunOptions(map=str(copy), scenario=scenario))
    assert world.map.name == "junction"


def test_explicit_map_of_another_name_is_a_clear_error(tmp_path: Path) -> None:
    scenario = scenario_file(tmp_path, "straight")
    with pytest.raises(StartupError) as caught:
        build_world(RunOptions(map="town", scenario=scenario))
    assert str(caught.value) == (
        f"{scenario}:1: map: the scenario is for map 'straight', --map gives 'town' "
        "(leave --map out to run the scenario's own map)"
    )


def test_no_scenario_no_map_is_the_town_with_its_scenario() -> None:
    world = build_world(RunOptions())
    assert world.map.name == "town"
    assert len(world.npcs) > 0


def test_scenario_naming_a_missing_map_path_names_it(tmp_path: Path) -> None:
    with pytest.raises(StartupError) as caught:
        build_world(RunOptions(scenario=scenario_file(tmp_path, "maps/nowhere")))
    assert f"{tmp_path / 'maps' / 'nowhere'}: no such file or folder" in str(caught.value)


def test_cli_conflict_is_one_line_before_anything_starts(tmp_path: Path) -> None:
    scenario = scenario_file(tmp_path, "straight")
    result = subprocess.run(
        [sys.executable, "-m", "egosim", "run", "--map", "loop", "--scenario", str(scenario)],
        env={"ROS_MASTER_URI": f"http://127.0.0.1:{free_port()}/", "PATH": "/usr/bin:/bin"},
        capture_output=True,
        text=True,
        timeout=60,
        check=False,
    )
    assert result.returncode == 2
    assert result.stderr.strip() == (
        f"egosim: {scenario}:1: map: the scenario is for map 'straight', --map gives 'loop' "
        "(leave --map out to run the scenario's own map)"
    )


def test_a_scenario_naming_its_map_by_path_loads_on_that_map_over_the_network() -> None:
    # ScenarioLoad hands the world a parsed file: the path's last part is the map's name.
    world = World(load_map("mgeo_sample"))
    scenario = parse_scenario("map: ../maps/mgeo_sample/\nego: {start: {lane: R3_E_1}}\n")
    assert scenario.map_name == "mgeo_sample"
    assert world.load_scenario(scenario).ego_placed
