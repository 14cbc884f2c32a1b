"""Values of an OpenSCENARIO file's parameters reach the run's world: `egosim run --param
NAME=VALUE`, and each case of a ParameterValueDistribution sweep as the batch worker reads
it from its case file."""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import pytest

from egosim.app.options import RunOptions
from egosim.app.runner import build_world
from egosim.batch.case import CaseSpec
from egosim.batch.suite import scenario_suite
from egosim.cli.run import parameter_assignment
from egosim.world.openscenario import ScenarioRun

GALLERY = Path(__file__).parents[2] / "examples" / "openscenario"
BRAKING_TARGET = GALLERY / "braking_target.xosc"


def started(options: RunOptions) -> ScenarioRun:
    run = build_world(options).storyboard
    assert isinstance(run, ScenarioRun)
    return run


def gap(run: ScenarioRun) -> float:
    """Free space from the ego's front to the target's rear (both face east)."""
    ego, target = run.rt.entity("Ego"), run.rt.entity("Target")
    ego_front = ego.box_centre()[0] + ego.definition.length / 2
    return target.box_centre()[0] - target.definition.length / 2 - ego_front


def test_param_arguments_are_name_value_pairs() -> None:
    assert parameter_assignment("Headway=20") == ("Headway", "20")
    assert parameter_assignment(" Note =a=b") == ("Note", "a=b")
    for bad in ("Headway", "=20"):
        with pytest.raises(argparse.ArgumentTypeError, match="expected NAME=VALUE"):
            parameter_assignment(bad)


def test_a_param_replaces_the_declared_value_and_what_derives_from_it() -> None:
    declared = started(RunOptions(scenario=BRAKING_TARGET))
    assert gap(declared) == pytest.approx(12.0)
    given = started(
        RunOptions(
            scenario=BRAKING_TARGET,
            scenario_parameters=(("Headway", "20"), ("TestSpeed_kph", "36")),
        )
    )
    assert gap(given) == pytest.approx(20.0)
    assert given.rt.entity("Target").speed == pytest.approx(10.0)  # _TestSpeed = 36 / 3.6


def test_each_sweep_case_runs_with_its_own_values(tmp_path: Path) -> None:
    cases = scenario_suite(GALLERY / "braking_target_sweep.xosc", "true", 20.0, "sim")
    speeds = []
    for case in cases:
        # The worker reads its case from a JSON file, as the batch writes it.
        case_file = tmp_path / f"{case.name}.json"
        case_file.write_text(json.dumps(case.as_dict()), encoding="utf-8")
        read = CaseSpec.from_dict(json.loads(case_file.read_text(encoding="utf-8")))
        run = started(
            RunOptions(
                scenario=Path(read.openscenario),
                scenario_parameters=tuple(read.scenario_parameters.items()),
            )
        )
        assert run.rt.parameters["Deceleration"] == float(case.scenario_parameters["Deceleration"])
        speeds.append(round(run.rt.entity("Target").speed * 3.6, 6))
    assert speeds == [30, 30, 40, 40, 50, 50]
