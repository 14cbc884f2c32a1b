"""Scenarios: the documented YAML format, its JSON Schema, parsing and placement.

Public API:
    parse_scenario(document, label) -> Scenario     YAML text or data, schema-validated
    load_default_scenario() -> Scenario             the built-in town's scenario
    scenario_schema() -> dict                       the JSON Schema
    Scenario, EgoSpec, NpcSpec, LaneChangeSpec, PedestrianSpec, ObstacleSpec, SignalsSpec,
    PoseStart, LaneStart
    ScenarioLoadOptions, ScenarioLoadReport         ScenarioLoad flags and outcome
    ScenarioError                                   names file, line and field
"""

from egosim.world.scenario.default import (
    DEFAULT_SCENARIO_FILE,
    default_scenario_text,
    load_default_scenario,
)
from egosim.world.scenario.errors import ScenarioError
from egosim.world.scenario.load_options import ScenarioLoadOptions, ScenarioLoadReport
from egosim.world.scenario.model import (
    EgoSpec,
    LaneChangeSpec,
    LaneStart,
    NpcSpec,
    ObstacleSpec,
    PedestrianSpec,
    PoseStart,
    Scenario,
    SignalsSpec,
)
from egosim.world.scenario.parse import parse_scenario, scenario_schema

__all__ = [
    "DEFAULT_SCENARIO_FILE",
    "EgoSpec",
    "LaneChangeSpec",
    "LaneStart",
    "NpcSpec",
    "ObstacleSpec",
    "PedestrianSpec",
    "PoseStart",
    "Scenario",
    "ScenarioError",
    "ScenarioLoadOptions",
    "ScenarioLoadReport",
    "SignalsSpec",
    "default_scenario_text",
    "load_default_scenario",
    "parse_scenario",
    "scenario_schema",
]
