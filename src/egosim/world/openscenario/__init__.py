"""ASAM OpenSCENARIO XML 1.0–1.3: reading a scenario file's text and running its
storyboard on a world (pure: files are read by the caller).

Public API:
    read_openscenario(text, label, catalog_files, parameters) -> OpenScenario
    catalog_directories(root) / root_of(text, label) / map_reference(root)
    OpenScenario.start(world, load_ego, kinds) -> ScenarioRun   (world.storyboard)
    ScenarioRun.step(dt, ego_driven), .finished, .outcome()
    read_distribution(text, label) -> Distribution   ParameterValueDistribution files
"""

from egosim.world.openscenario.catalogs import catalog_directories
from egosim.world.openscenario.distributions import Distribution, read_distribution
from egosim.world.openscenario.engine import ScenarioRun
from egosim.world.openscenario.program import (
    OpenScenario,
    choose_ego,
    map_reference,
    read_openscenario,
    root_of,
)
from egosim.world.scenario.model import Outcome

__all__ = [
    "Distribution",
    "OpenScenario",
    "Outcome",
    "ScenarioRun",
    "catalog_directories",
    "choose_ego",
    "map_reference",
    "read_distribution",
    "read_openscenario",
    "root_of",
]
