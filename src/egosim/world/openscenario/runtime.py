"""What a running scenario knows: its entities, parameters and variables, the time, and
the notes it has to report; positions, conditions and actions all read it."""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Protocol

from egosim.world.map import LaneMap
from egosim.world.map.lane_roads import road_coordinates_of
from egosim.world.map.road_coordinates import RoadCoordinates
from egosim.world.openscenario.entities import EntityState
from egosim.world.openscenario.expressions import Value
from egosim.world.openscenario.signal_controllers import SignalController
from egosim.world.scenario.model import StoryboardWorld


class UnknownEntityError(LookupError):
    """An action or condition names an entity the running scenario does not have: never
    declared, left out, or of a kind the load left out (ScenarioLoad's flags)."""

    def __init__(self, name: str) -> None:
        super().__init__(f"no entity {name!r} in the running scenario")


class ElementState(Protocol):
    """A storyboard element as StoryboardElementStateCondition sees it."""

    state: str
    """standbyState, runningState or completeState."""

    def transitioned(self, transition: str, tick: int) -> bool: ...


@dataclass
class Runtime:
    world: StoryboardWorld
    entities: dict[str, EntityState]
    parameters: dict[str, Value]
    variables: dict[str, Value]
    ego: str | None
    """The entity that is egosim's main ego."""
    time: float = 0.0
    tick: int = 0
    elements: dict[tuple[str, str], ElementState] = field(default_factory=dict)
    """Storyboard elements by (type, name): story, act, maneuverGroup, maneuver, event,
    action."""
    notes: list[str] = field(default_factory=list)
    """Lines to report (each once), oldest first; the caller empties it."""
    signal_controllers: dict[str, SignalController] = field(default_factory=dict)
    """RoadNetwork's TrafficSignalControllers, by name."""
    ego_driven: bool = False
    """The scenario drives the ego this step (its control mode is auto)."""
    _noted: set[str] = field(default_factory=set)

    @property
    def lane_map(self) -> LaneMap:
        return self.world.map

    @property
    def roads(self) -> RoadCoordinates:
        return road_coordinates_of(self.world.map)

    def entity(self, name: str) -> EntityState:
        try:
            return self.entities[name]
        except KeyError:
            raise UnknownEntityError(name) from None

    def note_once(self, text: str) -> None:
        if text not in self._noted:
            self._noted.add(text)
            self.notes.append(text)

    def present(self) -> Iterable[EntityState]:
        return (e for e in self.entities.values() if e.in_world())

    def scenario_drives(self, entity: EntityState) -> bool:
        """The scenario moves this entity (everyone but an ego its stack drives)."""
        return not entity.is_ego or self.ego_driven
