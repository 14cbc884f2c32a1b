"""The pure, deterministic simulation core: map, vehicles, traffic, signals, collisions.

Public API:
    World, Ego, EgoLaneState                 the assembly the bridge drives
    UnknownObjectModelError                  World.add_object's refusal
    egosim.world.map, .vehicle, .traffic, .signals, .scenario, .collision   the parts
    egosim.world.populations, .contact_handling   how World steps its agents
"""

from egosim.world.world import (
    DEFAULT_PHYSICS_STEP_S,
    Ego,
    EgoLaneState,
    UnknownObjectModelError,
    World,
)

__all__ = ["DEFAULT_PHYSICS_STEP_S", "Ego", "EgoLaneState", "UnknownObjectModelError", "World"]
