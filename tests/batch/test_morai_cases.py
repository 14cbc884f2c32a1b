"""Batch cases whose scenario is a MORAI SIM scenario file: swept `$parameters` and counts
over its lists, its map from mapInfo, one file run alone, a case's simulator reading the
JSON it is given."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import pytest
import yaml

from egosim.batch.errors import SuiteError
from egosim.batch.pool import run_local
from egosim.batch.suite import load_suite, scenario_suite
from tests import morai_scenarios as morai
from tests.batch.processes import processes_using

STAND_IN = f"{sys.executable} {Path(__file__).parent / 'peers' / 'listening_stack.py'}"


def morai_document() -> dict:
    return morai.scenario(
        "straight",
        morai.ego(morai.at_pose(10.0, -1.75, 0.0)),
        vehicles=tuple(
            morai.npc(morai.at_pose(60.0 + 30 * k, -1.75, 0.0), k, desired_kmh="$npc_kmh")
            for k in range(3)
        ),
        pedestrians=(morai.pedestrian(80.0, 9.0, -90.0, 9),),
    )


def write(folder: Path, suite: dict, document: dict) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    morai.write(folder, "scenario.json", document)
    path = folder / "suite.yaml"
    path.write_text(yaml.safe_dump(suite, sort_keys=False), encoding="utf-8")
    return path


def suite(**case: object) -> dict:
    return {
        "stack": {"command": "true"},
        "time_limit_s": 2,
        "parameters": {"npc_kmh": 30},
        "cases": [{"name": "follow", "scenario": "scenario.json", **case}],
    }


def test_a_morai_case_sweeps_its_parameters_and_counts_its_lists(tmp_path: Path) -> None:
    sweep = {"npc_kmh": [20, 40], "npc_count": [1, 3]}
    cases = load_suite(write(tmp_path, suite(sweep=sweep), morai_document()))
    assert [c.name for c in cases] == [
        f"follow[npc_kmh={kmh},npc_count={n}]" for kmh in (20, 40) for n in (1, 3)
    ]
    last = cases[-1]
    assert last.map == "straight"  # mapInfo.mapName, a map egosim knows by name
    assert [v["desiredVelocity"] for v in last.scenario["vehicleList"]] == [40, 40, 40]
    assert len(cases[0].scenario["vehicleList"]) == 1
    assert last.scenario["pedestrianList"][0]["UNIQUEID"] == 9


def test_a_morai_map_folder_beside_the_file_is_the_case_map(tmp_path: Path) -> None:
    document = morai_document()
    document["mapInfo"]["mapName"] = "R_KR_PG_K-City"
    (case,) = load_suite(write(tmp_path, suite(), document))
    assert case.map == str(tmp_path / "R_KR_PG_K-City")


@pytest.mark.parametrize(
    ("change", "message"),
    [
        ({"parameters": {}}, "the scenario uses $npc_kmh, not set"),
        ({"parameters": {"npc_kmh": "fast"}}, "vehicleList[0].desiredVelocity: 'fast' is not a"),
        ({"parameters": {"npc_kmh": 30, "seed": 3}}, "parameter 'seed' is used by neither"),
    ],
)
def test_mistakes_in_a_morai_case_are_located_errors(
    tmp_path: Path, change: dict, message: str
) -> None:
    with pytest.raises(SuiteError, match=r"suite\.yaml") as caught:
        load_suite(write(tmp_path, suite() | change, morai_document()))
    assert message in str(caught.value)


def test_a_broken_json_scenario_is_an_error_naming_its_line(tmp_path: Path) -> None:
    path = write(tmp_path, suite(), morai_document())
    (tmp_path / "scenario.json").write_text('{"mapInfo": {}\n"x": 1}', encoding="utf-8")
    with pytest.raises(SuiteError, match=r"scenario\.json:2: column 1"):
        load_suite(path)


def test_one_morai_file_runs_alone_as_one_case(tmp_path: Path) -> None:
    document = morai_document()
    for vehicle in document["vehicleList"]:
        vehicle["desiredVelocity"] = 30
    path = morai.write(tmp_path, "follow.json", document)
    (case,) = scenario_suite(path, "my_stack", 20.0, "sync")
    assert (case.name, case.map, case.clock, case.time_limit_s) == (
        "follow",
        "straight",
        "sync",
        20.0,
    )
    assert case.scenario == json.loads(path.read_text(encoding="utf-8"))


def test_a_morai_case_drives_on_the_scenario_it_was_given(tmp_path: Path) -> None:
    document = morai_document()
    document["vehicleList"][0]["isLaneChange"] = True
    suite_file = write(
        tmp_path / "suite",
        {
            "stack": {"command": f"{STAND_IN} exit 0 600", "connect_timeout_s": 15},
            "clock": {"mode": "sim", "rtf": 0},
            "time_limit_s": 2,
            "criteria": ["no_collision"],
            "cases": [
                {"name": "follow", "scenario": "scenario.json", "parameters": {"npc_kmh": 25}}
            ],
        },
        document,
    )
    out = tmp_path / "out"
    results = run_local(load_suite(suite_file), str(out), 1, lambda result, running: None)
    result = results["follow"]
    assert (result["status"], result["end"]) == ("passed", "time_limit")
    folder = out / result["folder"]
    given = json.loads((folder / "scenario.json").read_text(encoding="utf-8"))
    assert [v["desiredVelocity"] for v in given["vehicleList"]] == [25, 25, 25]
    log = (folder / "simulator.log").read_text(encoding="utf-8")
    assert "vehicleList[].isLaneChange: not carried out" in log
    assert processes_using(out) == []
