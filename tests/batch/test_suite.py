"""Suite files: sweeps expand into named cases, parameters reach the scenario and the
stack, mistakes are located errors."""

from __future__ import annotations

from pathlib import Path

import pytest

from egosim.batch.errors import SuiteError
from egosim.batch.suite import load_suite
from egosim.batch.sweep import parameter_sets
from tests.batch.suites import write_suite

TOWN = {
    "map": "town",
    "seed": 0,
    "ego": {"start": {"lane": "R5_E_2", "s": "$start_s"}},
    "npcs": [{"start": {"lane": "R5_E_1", "s": float(k * 20)}} for k in range(3)],
    "signals": {"default": {"green_s": "$green_s"}},
}


def suite(**overrides: object) -> dict:
    base = {
        "stack": {"command": "my_stack --speed {speed}"},
        "parameters": {"speed": 10, "start_s": 0.0, "green_s": 30.0},
        "cases": [{"name": "town", "scenario": "scenario.yaml"}],
    }
    base.update(overrides)
    return base


def test_a_sweep_is_the_product_of_its_lists_and_ranges_in_file_order(tmp_path: Path) -> None:
    cases = [
        {
            "name": "town",
            "scenario": "scenario.yaml",
            "sweep": {
                "seed": [1, 2],
                "speed": {"from": 5, "to": 15, "step": 5},
                "green_s": [20.5],
            },
        }
    ]
    specs = load_suite(write_suite(tmp_path, suite(cases=cases), TOWN))
    assert [c.name for c in specs] == [
        f"town[seed={seed},speed={speed},green_s=20.5]" for seed in (1, 2) for speed in (5, 10, 15)
    ]
    first = specs[0]
    assert first.scenario["seed"] == 1
    assert first.scenario["signals"]["default"]["green_s"] == 20.5
    assert first.scenario["ego"]["start"]["s"] == 0.0  # the suite's default
    assert first.placeholders("/c")["speed"] == "5"


def test_explicit_combinations_and_counts_cut_the_scenario_lists(tmp_path: Path) -> None:
    cases = [
        {
            "name": "traffic",
            "scenario": "scenario.yaml",
            "combinations": [{"npc_count": 0}, {"npc_count": 2, "start_s": 5.0}],
        }
    ]
    specs = load_suite(write_suite(tmp_path, suite(cases=cases), TOWN))
    assert [c.name for c in specs] == ["traffic[npc_count=0]", "traffic[npc_count=2,start_s=5]"]
    assert [len(c.scenario["npcs"]) for c in specs] == [0, 2]
    assert specs[1].scenario["ego"]["start"]["s"] == 5.0


def test_ranges_include_their_end_and_keep_fractions() -> None:
    assert parameter_sets({"v": {"from": 0.5, "to": 1.5, "step": 0.5}}, None) == [
        {"v": 0.5},
        {"v": 1.0},
        {"v": 1.5},
    ]
    assert parameter_sets(None, None) == [{}]


@pytest.mark.parametrize(
    ("change", "message"),
    [
        ({"criteria": ["route_completion >> 1"]}, "criteria[0]"),
        ({"criteria": ["speediness <= 1"]}, "unknown figure 'speediness'"),
        ({"scoring": {"penalties": {"honking": 0.5}}}, "no infraction 'honking'"),
        ({"clock": "fast"}, "clock"),
        (
            {"cases": [{"name": "a", "scenario": "scenario.yaml", "sweep": {"unused": [1]}}]},
            "parameter 'unused' is used by neither",
        ),
        (
            {"cases": [{"name": "a", "scenario": "missing.yaml"}]},
            "cannot read",
        ),
        (
            {"cases": [{"name": "a", "scenario": "scenario.yaml", "sweep": {"npc_count": [9]}}]},
            "npc_count must be 0..3",
        ),
        (
            {"cases": [{"name": "a", "scenario": "scenario.yaml"}] * 2},
            "two cases are named 'a'",
        ),
    ],
)
def test_mistakes_are_located_errors(tmp_path: Path, change: dict, message: str) -> None:
    path = write_suite(tmp_path, suite(**change), TOWN)
    with pytest.raises(SuiteError, match=r"suite\.yaml") as error:
        load_suite(path)
    assert message in str(error.value)


def test_a_scenario_made_invalid_by_a_parameter_names_the_case(tmp_path: Path) -> None:
    cases = [{"name": "bad", "scenario": "scenario.yaml", "sweep": {"start_s": [-1.0]}}]
    with pytest.raises(SuiteError, match=r"bad\[start_s=-1\]"):
        load_suite(write_suite(tmp_path, suite(cases=cases), TOWN))


def test_the_example_suite_loads() -> None:
    example = Path(__file__).parents[2] / "examples" / "batch" / "lap_suite.yaml"
    names = [case.name for case in load_suite(example)]
    assert names == [
        "lap[seed=1]",
        "lap[seed=2]",
        "speed[speed_kmh=25]",
        "speed[speed_kmh=40]",
        "cone",
        "hurried",
    ]
