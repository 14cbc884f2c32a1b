"""The scenario shipped with egosim for the built-in town."""

from __future__ import annotations

from importlib import resources

from egosim.world.scenario.model import Scenario
from egosim.world.scenario.parse import parse_scenario

DEFAULT_SCENARIO_FILE = "default_town.yaml"


def default_scenario_text() -> str:
    return resources.files(__package__).joinpath(DEFAULT_SCENARIO_FILE).read_text("utf-8")


def load_default_scenario() -> Scenario:
    """A few NPCs driving round the town, pedestrians walking, obstacles, lights cycling."""
    return parse_scenario(default_scenario_text(), DEFAULT_SCENARIO_FILE)
