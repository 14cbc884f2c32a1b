"""A parsed scenario: what to place on the map and how the lights run, SI units."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import PurePath
from typing import Protocol

from egosim.json_value import JsonObject
from egosim.world.map import LaneMap
from egosim.world.map.georef import GeoReference
from egosim.world.populations import Ego
from egosim.world.scenario.errors import ScenarioError
from egosim.world.signals import IntersectionProgram, PhaseTiming, TrafficSignals
from egosim.world.traffic.scripted import ScriptedObjects
from egosim.world.vehicle import Gear
from egosim.yamltext import FieldPath, YamlDocument


@dataclass(frozen=True)
class PoseStart:
    """A position (m) and heading (rad, counter-clockwise from east)."""

    x: float
    y: float
    z: float = 0.0
    heading: float = 0.0


@dataclass(frozen=True)
class LaneStart:
    """Station s (m) along a lane, `lateral` m left of its centreline; `ratio` (0..1)
    gives the station as a fraction of the lane's length instead."""

    lane: str
    s: float = 0.0
    lateral: float = 0.0
    ratio: float | None = None


Start = PoseStart | LaneStart


@dataclass(frozen=True)
class EgoSpec:
    path: FieldPath
    model: str
    start: Start
    speed: float = 0.0
    """m/s."""
    gear: Gear | None = None
    """The gear the ego is put in; None: the one it is in."""


@dataclass(frozen=True)
class LaneChangeSpec:
    """Move into `lane`, a lane beside the NPC's, `after_s` s after the load (or as soon
    after as the NPC drives beside it), sliding across over `duration_s` s."""

    lane: str
    after_s: float = 0.0
    duration_s: float = 3.0


@dataclass(frozen=True)
class NpcSpec:
    path: FieldPath
    model: str
    start: Start
    speed: float = 0.0
    """Initial speed, m/s."""
    target_speed: float | None = None
    """m/s; None: speed_factor times each lane's limit."""
    speed_factor: float = 1.0
    route: tuple[str, ...] = ()
    start_delay_s: float = 0.0
    stalled: bool = False
    """Stands where it is placed for the whole scenario (a broken-down car)."""
    lane_change: LaneChangeSpec | None = None
    active_distance: float | None = None
    """Stands still until an ego comes within this many metres; None: moves at once."""


@dataclass(frozen=True)
class PedestrianSpec:
    """Walks a sidewalk, a crosswalk (back and forth) or scripted waypoints."""

    path: FieldPath
    model: str
    speed: float
    start_s: float = 0.0
    sidewalk: str | None = None
    crosswalk: str | None = None
    waypoints: tuple[tuple[float, float], ...] | None = None
    loop: bool = True
    active_distance: float | None = None
    """Waits until an ego comes within this many metres of `wake_point`; None: walks at
    once."""
    wake_point: tuple[float, float] | None = None
    """Where that distance is measured from; None: the start of the walk."""


@dataclass(frozen=True)
class ObstacleSpec:
    path: FieldPath
    model: str
    pose: PoseStart
    size: tuple[float, float, float] | None = None
    """length, width, height, m; None: the model's size."""


@dataclass(frozen=True)
class SignalStart:
    """The `index`-th signalised intersection of the map (by ascending id, from 0) starts
    its program in phase `phase`, `elapsed_s` s into it (a MORAI scenario's traffic
    light entry); `path` is that entry."""

    path: FieldPath
    index: int
    phase: int
    elapsed_s: float = 0.0


@dataclass(frozen=True)
class SignalsSpec:
    default: PhaseTiming = field(default_factory=PhaseTiming)
    intersections: dict[int, IntersectionProgram] = field(default_factory=dict)
    paths: dict[int, FieldPath] = field(default_factory=dict)
    """Where each intersection's entry sits in the file."""
    starts: tuple[SignalStart, ...] = ()
    """Where programs start, naming intersections by their place in the map's order."""


@dataclass(frozen=True)
class Outcome:
    """How a scenario stands: its storyboard's state and MORAI's evaluation verdict."""

    state: str
    """"running", "stopped" (its StopTrigger fired), "success" or "failure" (an
    evaluation group fired)."""
    time: float
    """Scenario time of the end (or now, while running), s."""
    verdict: str | None
    """"success", "failure", or None: no evaluation, or none of its groups fired."""


class StoryboardRun(Protocol):
    """An OpenSCENARIO storyboard running on a world (egosim.world.openscenario), stepped
    once per tick before the world (the tick pipeline's storyboard stage)."""

    @property
    def finished(self) -> bool:
        """Its StopTrigger (or an evaluation group) has ended the scenario."""
        ...

    def outcome(self) -> Outcome:
        """Its state now (or at its end) and its evaluation's verdict."""
        ...

    def step(self, dt: float, ego_driven: bool) -> list[str]:
        """Advance dt s; ego_driven: the scenario drives the ego this step. Returns the
        lines to report (each once)."""
        ...


class EgoLanePlace(Protocol):
    """Where an ego sits on its lane, as a storyboard reads it."""

    @property
    def lane_id(self) -> str: ...

    @property
    def s(self) -> float: ...

    @property
    def lateral_offset(self) -> float: ...


class StoryboardWorld(Protocol):
    """What a running storyboard uses of the world it runs on (egosim.world.World, whose
    module imports this one)."""

    @property
    def map(self) -> LaneMap: ...

    @property
    def signals(self) -> TrafficSignals: ...

    @property
    def egos(self) -> list[Ego]: ...

    @property
    def scripted(self) -> ScriptedObjects: ...

    @property
    def scripted_egos(self) -> set[int]:
        """The egos the storyboard moves (their stacks' commands are not applied)."""
        ...

    @property
    def command_timeout_s(self) -> float | None: ...

    def reserve_ids(self, count: int) -> list[int]: ...

    def ego_lane_state(self, index: int = 0) -> EgoLanePlace: ...


class StoryboardProgram(Protocol):
    """A storyboard ready to run: `start` places its entities (its Init) on a world."""

    def start(
        self, world: StoryboardWorld, load_ego: bool, kinds: frozenset[str], drives_ego: bool
    ) -> StoryboardRun:
        """Run Init on `world`; load_ego: place the ego as Init says; kinds: the entity
        kinds to create (vehicle, pedestrian, miscellaneous object); drives_ego: the
        scenario drives the ego (its control mode is auto)."""
        ...


def map_name_of(reference: str) -> str:
    """The name of the map a scenario's `map` field refers to: a map name as it is, a
    path its last part (`maps/kcity/` -> `kcity`, `maps/track.xodr` -> `track`)."""
    name = PurePath(reference).name or reference
    return name[: -len(".xodr")] if name.lower().endswith(".xodr") else name


@dataclass(frozen=True)
class Scenario:
    map_name: str
    """The map's name, compared with the name of the map the world runs."""
    seed: int = 0
    ego: EgoSpec | None = None
    npcs: tuple[NpcSpec, ...] = ()
    pedestrians: tuple[PedestrianSpec, ...] = ()
    obstacles: tuple[ObstacleSpec, ...] = ()
    signals: SignalsSpec = field(default_factory=SignalsSpec)
    network: JsonObject | None = None
    """The file's network settings, handed to the simulator as they are."""
    map_reference: str = ""
    """The `map` field as written: a map name, or a path relative to the scenario file
    (what `egosim run --scenario FILE` loads); empty: `map_name`."""
    source: YamlDocument = field(
        default_factory=lambda: YamlDocument("<scenario>", None, error_type=ScenarioError)
    )
    storyboard: StoryboardProgram | None = None
    """An OpenSCENARIO file's storyboard (its entities and what they do)."""
    origin: GeoReference | None = None
    """The frame the file's positions are in (a MORAI scenario's map offsets), when the
    file says; a load moves them into the map's frame. None: the map's own frame."""

    field_names: Mapping[str, str] = field(default_factory=dict)
    """What the file calls the fields errors name, where it is not egosim's YAML (a MORAI
    file's start is its `initPosition`, a lane its `initLink`)."""

    def error(self, path: FieldPath, message: str) -> ScenarioError:
        """An error naming this scenario's file, the line of `path` and the field."""
        path = tuple(self.field_names.get(p, p) if isinstance(p, str) else p for p in path)
        error = self.source.error(path, message)
        if isinstance(error, ScenarioError):
            return error
        # A source made without error_type=ScenarioError still raises what callers catch.
        return ScenarioError(error.label, error.line, error.field, error.message)
