"""MORAI SIM scenario files through ScenarioLoad: named with or without `.json` inside the
data roots, each flag honoured as for YAML, what is not carried out logged once, a bad
file refused with its line or JSON path."""

from __future__ import annotations

import logging
from pathlib import Path
from typing import Any

import pytest

from egosim.bridge import simulation_context
from egosim.bridge.context import BridgeContext
from egosim.bridge.scene.scenarios import (
    on_scenario_load,
    prepare_scenario,
    prepare_scenario_service,
    serve_scenario_load,
)
from egosim.maps import load_map
from egosim.msgs import get_profile
from egosim.world import World
from egosim.world.vehicle import Gear
from tests import morai_scenarios as morai

PROFILE = get_profile("26.r1")
ALL_KINDS = {
    "load_ego_vehicle_data": True,
    "load_surrounding_vehicle_data": True,
    "load_pedestrian_data": True,
    "load_obstacle_data": True,
}


@pytest.fixture
def roots(tmp_path: Path) -> Path:
    document = morai.scenario(
        "straight",
        morai.ego(morai.at_pose(120.0, -1.75, 0.0), gear=1, kmh=18.0),
        vehicles=(
            morai.npc(morai.on_link("R1_E_1", 0.2), 1, desired_kmh=40.0, isLaneChange=True),
            morai.npc(morai.at_pose(300.0, 1.75, 180.0), 2, data_id=30200003),
        ),
        pedestrians=(morai.pedestrian(150.0, 9.0, -90.0, 3),),
        objects=(morai.thing(160.0, -5.25, 0.0, 4, 40100005),),
    )
    morai.write(tmp_path, "two_cars.json", document)
    return tmp_path


def context_of(roots: Path) -> tuple[World, BridgeContext]:
    world = World(load_map("straight"))
    return world, simulation_context(world, data_roots=(roots,))


def load(context: BridgeContext, name: str, **flags: Any) -> None:
    request = PROFILE.message("morai_msgs/ScenarioLoad").new(file_name=name, **flags)
    row = context.row("scenario_load")
    on_scenario_load(context, row, prepare_scenario(context, row, request))


def counts(world: World) -> tuple[int, int, int]:
    return len(world.npcs), len(world.pedestrians), len(world.obstacles)


def test_a_bare_name_finds_the_json_file_and_places_everything(roots: Path) -> None:
    world, context = context_of(roots)
    load(context, "two_cars", delete_all=True, **ALL_KINDS)
    assert counts(world) == (2, 1, 1)
    assert sorted(world.npcs.names) == ["2016_Hyundai_Ioniq", "2016_Kia_Niro(HEV)"]
    status = world.ego_status()
    assert (status.pose.x, status.pose.y, status.velocity[0]) == pytest.approx((120.0, -1.75, 5.0))
    assert world.egos[0].vehicle.gear is Gear.PARKING
    assert not world.paused


def test_each_flag_is_honoured(roots: Path) -> None:
    world, context = context_of(roots)
    before = world.ego_status().pose
    load(context, "two_cars.json", delete_all=True, load_surrounding_vehicle_data=True)
    assert counts(world) == (2, 0, 0)
    assert world.ego_status().pose == before  # load_ego_vehicle_data was not set
    load(
        context,
        "two_cars.json",
        delete_all=False,
        load_pedestrian_data=True,
        load_obstacle_data=True,
        set_pause=True,
    )
    assert counts(world) == (2, 1, 1)  # joined what was there
    assert world.paused
    load(context, "two_cars", delete_all=True, load_ego_vehicle_data=True)
    assert counts(world) == (0, 0, 0)
    assert world.ego_status().pose.x == pytest.approx(120.0)


def test_a_network_request_on_a_file_without_network_settings_changes_nothing(
    roots: Path,
) -> None:
    world, context = context_of(roots)
    settings = context.settings
    load(context, "two_cars", delete_all=True, load_network_connection_data=True, **ALL_KINDS)
    assert context.settings == settings
    assert world.network_settings_request is None


def test_what_is_not_carried_out_is_logged_once_per_field(
    roots: Path, caplog: pytest.LogCaptureFixture
) -> None:
    _, context = context_of(roots)
    with caplog.at_level(logging.WARNING):
        load(context, "two_cars", delete_all=True, **ALL_KINDS)
    lane_change = [r.message for r in caplog.records if "isLaneChange" in r.message]
    assert len(lane_change) == 1
    assert lane_change[0].endswith(
        "vehicleList[].isLaneChange: not carried out: egosim's NPCs change lanes only when "
        "a scenario says so (vehicleList[0])"
    )
    assert lane_change[0].startswith(str(roots / "two_cars.json"))


def test_the_service_refuses_a_broken_file_naming_its_line(
    roots: Path, caplog: pytest.LogCaptureFixture
) -> None:
    (roots / "broken.json").write_text('{\n  "mapInfo": {"mapName": "straight"},\n}\n', "utf-8")
    (roots / "wrong.json").write_text(
        morai.text(morai.scenario("straight", vehicles=({"DataID": 30100010},))), "utf-8"
    )
    world, context = context_of(roots)
    row = context.row("scenario_load_srv")
    message = PROFILE.message("morai_msgs/MoraiScenarioLoadSrvRequest")
    results = []
    with caplog.at_level(logging.ERROR):
        for name in ("broken", "wrong", "../outside.json", "two_cars"):
            request = message.new(
                request=PROFILE.message("morai_msgs/ScenarioLoad").new(file_name=name, **ALL_KINDS)
            )
            prepared = prepare_scenario_service(context, row, request)
            results.append(serve_scenario_load(context, row, prepared).response.result)
    assert results == [False, False, False, True]
    assert "broken.json:3: column 1: Expecting property name" in caplog.text
    assert "wrong.json: vehicleList[0].initPosition: missing" in caplog.text
    assert "outside the data roots" in caplog.text
    assert counts(world) == (2, 1, 1)
