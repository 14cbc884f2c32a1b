"""Every kind of agent behind one interface (Population), simulated or recorded.

Public API:
    Population, Replaceable, EgoPopulation, Surroundings, LanePoints, Shove
                                                   the interface (base.py)
    Ego, SimulatedEgos, ReplayedEgos               the egos; the main one replayed
    SimulatedNpcs, PlacedGhosts, SimulatedPedestrians, SimulatedObstacles
                                                   world/traffic's agents
    ScriptedPopulation, ScriptedRoadUsers          what a storyboard places
    RecordedVehicles, RecordedPedestrians, RecordedObstacles
                                                   a replay's recorded tables
"""

from egosim.world.populations.base import (
    EgoPopulation,
    LanePoints,
    Population,
    Replaceable,
    Shove,
    Surroundings,
    place_on_lanes,
)
from egosim.world.populations.egos import Ego, ReplayedEgos, SimulatedEgos
from egosim.world.populations.recorded import (
    RecordedObstacles,
    RecordedPedestrians,
    RecordedPopulation,
    RecordedVehicles,
)
from egosim.world.populations.scripted import ScriptedPopulation, ScriptedRoadUsers
from egosim.world.populations.simulated import (
    PlacedGhosts,
    SimulatedNpcs,
    SimulatedObstacles,
    SimulatedPedestrians,
)

__all__ = [
    "Ego",
    "EgoPopulation",
    "LanePoints",
    "PlacedGhosts",
    "Population",
    "RecordedObstacles",
    "RecordedPedestrians",
    "RecordedPopulation",
    "RecordedVehicles",
    "Replaceable",
    "ReplayedEgos",
    "ScriptedPopulation",
    "ScriptedRoadUsers",
    "Shove",
    "SimulatedEgos",
    "SimulatedNpcs",
    "SimulatedObstacles",
    "SimulatedPedestrians",
    "Surroundings",
    "place_on_lanes",
]
