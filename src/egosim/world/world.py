"""The World: map, ego vehicles, traffic, signals and collisions advanced by step(dt).

A thin assembly of the modules that hold the logic. Its agents are populations
(world/populations): the egos, then the NPC vehicles (simulated, ghosts, a storyboard's),
the pedestrians (simulated, a storyboard's) and the obstacles (likewise), in the order
of the object table; a replay swaps a recorded population in for a kind's own ones. The
world orders them, steps them and keeps the logs; world/contact_handling.py answers
their contacts. It is pure and deterministic: the same scenario, seed and command
sequence give bit-identical states.
"""

from __future__ import annotations

import itertools
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass

import numpy as np

from egosim.json_value import JsonObject
from egosim.world.collision import EgoCollision, VehicleCollision
from egosim.world.contact import ContactModel
from egosim.world.contact_handling import ContactHandler, StepContacts
from egosim.world.map import LaneMap, ProjectionMemory
from egosim.world.populations import (
    Ego,
    EgoPopulation,
    PlacedGhosts,
    Population,
    RecordedObstacles,
    RecordedPedestrians,
    RecordedVehicles,
    Replaceable,
    ReplayedEgos,
    ScriptedPopulation,
    ScriptedRoadUsers,
    SimulatedEgos,
    SimulatedNpcs,
    SimulatedObstacles,
    SimulatedPedestrians,
    Surroundings,
)
from egosim.world.recorded_scene import RecordedScene
from egosim.world.scenario import Scenario, ScenarioLoadOptions, ScenarioLoadReport
from egosim.world.scenario.frame import in_map_frame
from egosim.world.scenario.model import StoryboardRun
from egosim.world.scenario.placement import (
    check_map,
    ego_placement,
    npc_spawns,
    obstacle_spawns,
    pedestrian_spawns,
)
from egosim.world.signals import (
    IntersectionProgram,
    LightState,
    TrafficSignals,
    UnknownPhaseError,
    governing_light_id,
)
from egosim.world.traffic import (
    CrosswalkLights,
    LaneGraph,
    LightsView,
    NearestObjects,
    NpcFleet,
    ObjectList,
    ObjectState,
    ObjectTable,
    ObjectType,
    PedestrianCrowd,
    SceneObjects,
    StaticObstacles,
    closest_objects,
    crossed_lights,
)
from egosim.world.traffic.catalogue import OBSTACLE_MODELS
from egosim.world.traffic.ghosts import GhostPlacement, NpcGhosts
from egosim.world.traffic.npc_vehicles import NpcSpawn
from egosim.world.traffic.obstacles import ObstacleSpawn
from egosim.world.traffic.pedestrians import PedestrianSpawn
from egosim.world.traffic.scripted import ScriptedObjects
from egosim.world.vehicle import (
    DEFAULT_EGO_MODEL,
    EgoModel,
    Pose,
    VehicleStatus,
    ego_model,
    ego_vehicle,
)
from egosim.world.vehicle.catalogue import VEHICLE_CATALOGUE
from egosim.yamltext import Problems

DEFAULT_PHYSICS_STEP_S = 0.01
DEFAULT_OBJECT_LIST_SIZE = 20


class UnknownObjectModelError(ValueError):
    """A model name that is neither an obstacle nor a vehicle of the catalogues."""

    def __init__(self, name: str) -> None:
        known = ", ".join(sorted([*OBSTACLE_MODELS, *VEHICLE_CATALOGUE]))
        super().__init__(f"unknown object model {name!r}; known: {known}")


@dataclass(frozen=True)
class EgoLaneState:
    """Where an ego sits on its lane (EgoVehicleStatus's lane fields), m."""

    lane_id: str
    s: float
    lateral_offset: float
    """From the lane centreline, left positive."""
    distance_left: float
    """From the vehicle's reference point to the lane's left boundary."""
    distance_right: float
    cross_track_error: float
    """From the lane centreline, right positive (= -lateral_offset)."""


class World:
    """Everything that moves, on one map; step(dt) advances it."""

    def __init__(
        self,
        lane_map: LaneMap,
        scenario: Scenario | None = None,
        *,
        physics_step_s: float = DEFAULT_PHYSICS_STEP_S,
        object_list_size: int = DEFAULT_OBJECT_LIST_SIZE,
    ) -> None:
        self.map = lane_map
        self.physics_step_s = physics_step_s
        self.object_list_size = object_list_size
        self.sim_time = 0.0
        self.paused = False
        self.signals = TrafficSignals(lane_map)
        graph = LaneGraph(lane_map, self.signals.lane_signals.of_lane)
        light_positions = {light_id: k for k, light_id in enumerate(self.signals.light_ids)}
        self.npcs = NpcFleet(graph, np.random.default_rng(0))
        self.npc_ghosts = NpcGhosts()
        self.pedestrians = PedestrianCrowd()
        self.obstacles = StaticObstacles()
        self.scripted = ScriptedObjects()
        """The vehicles, pedestrians and objects a storyboard places at every step."""
        self.scripted_egos: set[int] = set()
        """Egos (unique ids) whose pose a storyboard places: not stepped, immovable."""
        self.storyboard: StoryboardRun | None = None
        """The running OpenSCENARIO storyboard of the last scenario loaded, if it has one
        (the tick pipeline's storyboard stage steps it)."""
        self._next_id = 1
        self._command_timeout_s: float | None = None
        self.egos: list[Ego] = []
        self._simulated_egos = SimulatedEgos(lane_map, self.egos, self.scripted_egos)
        self._own: tuple[tuple[Replaceable, ...], ...] = (
            (
                SimulatedNpcs(self.npcs),
                PlacedGhosts(self.npc_ghosts),
                ScriptedRoadUsers(self.scripted, ObjectType.NPC_VEHICLE),
            ),
            (
                SimulatedPedestrians(
                    self.pedestrians, CrosswalkLights(crossed_lights(lane_map, light_positions))
                ),
                ScriptedRoadUsers(self.scripted, ObjectType.PEDESTRIAN),
            ),
            (
                SimulatedObstacles(self.obstacles, lane_map),
                ScriptedPopulation(self.scripted, ObjectType.OBSTACLE),
            ),
        )
        """Per kind (NPC vehicles, pedestrians, obstacles): the populations of the world's
        own agents (simulated, placed by NpcGhostCmd, placed by a storyboard)."""
        self.recorded = RecordedScene()
        """What a replay shows instead of simulating (nothing by default); see show_recorded."""
        self._show(self._simulated_egos, self._own)
        self.add_ego(DEFAULT_EGO_MODEL, self._first_lane_pose())
        self.contact_model = ContactModel()
        """Restitution and friction of every contact (world/contact.py)."""
        self.ego_collisions: dict[int, EgoCollision] = {}
        """Most recent collision of each ego, by the ego's unique id."""
        self.ego_collision_log: list[EgoCollision] = []
        """Every ego collision since the objects were last deleted, oldest first."""
        self.vehicle_collisions: list[VehicleCollision] = []
        """Every NPC-NPC collision since the objects were last deleted, oldest first."""
        self.ego_contacts: dict[int, list[ObjectState]] = {}
        """What each ego (by unique id) touches now, as it is now: contacts that last."""
        self.vehicle_contacts: list[VehicleCollision] = []
        """The NPC-NPC contacts of now, time-stamped when they began."""
        self.network_settings_request: JsonObject | None = None
        """The network settings of the last ScenarioLoad that asked for them."""
        self._contacts = ContactHandler(self.objects())
        self._lights: tuple[TrafficSignals, int, LightsView] | None = None
        self._lane_memory = ProjectionMemory()
        """The lane projection of the agents' last step: who has not moved since is not
        placed on a lane again."""
        if scenario is not None:
            self.load_scenario(scenario)

    def _first_lane_pose(self) -> Pose:
        x, y, z, heading = self.map.pose_at(self.map.lane_ids[0], 0.0)
        return Pose(x=x, y=y, z=z, yaw=heading)

    def _allocate_ids(self) -> Iterator[int]:
        return itertools.count(self._next_id)

    def reserve_ids(self, count: int) -> list[int]:
        """`count` fresh object ids (a storyboard's entities)."""
        ids = list(range(self._next_id, self._next_id + count))
        self._next_id += count
        return ids

    def _show(self, egos: EgoPopulation, kinds: tuple[tuple[Population, ...], ...]) -> None:
        """From now on the world's agents are `egos`, then the populations of each kind;
        those of its own populations that a recording stands in for wait meanwhile."""
        self._egos = egos
        self._kinds = kinds
        self._populations: tuple[Population, ...] = (egos, *itertools.chain(*kinds))
        shown = {id(population) for population in self._populations}
        self._waiting = tuple(
            population for population in itertools.chain(*self._own) if id(population) not in shown
        )

    # -- egos ------------------------------------------------------------------------

    def add_ego(self, model: str | EgoModel, pose: Pose) -> Ego:
        """A further ego vehicle (the first one is the main ego), of a catalogue model
        named or given."""
        chosen = ego_model(model) if isinstance(model, str) else model
        vehicle = ego_vehicle(chosen, pose, self._command_timeout_s)
        ego = Ego(self._next_id, vehicle)
        self._next_id += 1
        self.egos.append(ego)
        return ego

    @property
    def command_timeout_s(self) -> float | None:
        """Every ego's dead-man timeout: s of simulation time without a command before it
        brakes (stops); None, the default: the last command holds until the next one."""
        return self._command_timeout_s

    @command_timeout_s.setter
    def command_timeout_s(self, seconds: float | None) -> None:
        self._command_timeout_s = seconds
        for ego in self.egos:
            ego.vehicle.command_timeout = seconds

    def keep_egos(self, count: int) -> None:
        """Remove the egos after the first `count` (the main ego always stays)."""
        del self.egos[max(count, 1) :]

    def ego_status(self, index: int = 0) -> VehicleStatus:
        """The ego's state; a replayed main ego reports its recorded acceleration and pedals."""
        return self._egos.status(index)

    def ego_lane_state(self, index: int = 0) -> EgoLaneState:
        projection = self._egos.lanes()[index]
        return EgoLaneState(
            lane_id=projection.lane_id,
            s=projection.s,
            lateral_offset=projection.lateral,
            distance_left=projection.distance_left,
            distance_right=projection.distance_right,
            cross_track_error=-projection.lateral,
        )

    def ego_traffic_light(self, index: int = 0) -> LightState | None:
        """GetTrafficLightStatus: the light governing the lane ahead of the ego, else the
        nearest light; None on a map without lights."""
        pose = self.ego_status(index).pose
        lane = self.ego_lane_state(index)
        light_id = governing_light_id(self.map, lane.lane_id, lane.s, pose.x, pose.y)
        return None if light_id is None else self.signals.light(light_id)

    def ego_collision(self, index: int = 0) -> EgoCollision | None:
        """CollisionData: the most recent collision of this ego, None if it never had one."""
        return self.ego_collisions.get(self.egos[index].unique_id)

    # -- objects -----------------------------------------------------------------------

    def shown_tables(self) -> list[ObjectTable]:
        """NPCs, pedestrians and obstacles in view: the recorded ones where a replay shows
        them, else the world's own (simulated, ghosts, a storyboard's)."""
        return [_joined([population.table() for population in kind]) for kind in self._kinds]

    def objects(self) -> ObjectTable:
        """Every object: egos, then NPCs, pedestrians and obstacles."""
        return self.scene_objects().table

    def scene_objects(self) -> SceneObjects:
        """Every object (`objects`), with how many of its rows are of each kind."""
        egos = self._egos.table()
        kinds = [[population.table() for population in kind] for kind in self._kinds]
        table = ObjectTable.concatenate([egos, *itertools.chain(*kinds)])
        counts = tuple(sum(len(part) for part in kind) for kind in kinds)
        return SceneObjects(table, len(egos), (counts[0], counts[1], counts[2]))

    def object_list(self, ego_index: int = 0, size: int | None = None) -> ObjectList:
        """ObjectStatusList: counts of all spawned objects; the `size` (default
        object_list_size) objects closest to the ego, split by kind, closest first. The
        other egos count and appear among the vehicles.

        Closest is measured as a client measures it from the two messages: from the ego's
        reported position (its reference point, /Ego_topic's position) to each object's
        reported position (its footprint centre, ObjectStatus.position), in the plane.
        """
        return self.nearest_objects(ego_index, size).object_list()

    def nearest_objects(
        self, ego_index: int = 0, size: int | None = None, scene: SceneObjects | None = None
    ) -> NearestObjects:
        """`object_list` as rows of the object table: of `scene`, the world's
        scene_objects() as they are now when the caller has them already."""
        scene = self.scene_objects() if scene is None else scene
        table = scene.table
        candidates = np.ones(len(table), dtype=bool)
        candidates[: scene.egos] = table.unique_ids[: scene.egos] != self.egos[ego_index].unique_id
        other_egos = int(np.count_nonzero(candidates[: scene.egos]))
        pose = self.ego_status(ego_index).pose
        npcs, pedestrians, obstacles = scene.kinds
        return closest_objects(
            table,
            np.flatnonzero(candidates),
            (pose.x, pose.y),
            self.object_list_size if size is None else size,
            counts=(other_egos + npcs, pedestrians, obstacles),
        )

    def place_npc_ghosts(self, placements: Sequence[GhostPlacement]) -> list[int]:
        """NpcGhostCmd: each placed NPC leaves the simulation and stands where it is told;
        an unknown id becomes a new NPC. Returns the ids refused: those of an ego, a
        pedestrian or an obstacle."""
        taken = {ego.unique_id for ego in self.egos}
        taken.update(self.scripted.unique_ids())
        taken.update(int(i) for i in self.pedestrians.unique_ids)
        taken.update(int(i) for i in self.obstacles.table().unique_ids)
        accepted = [p for p in placements if p.unique_id not in taken]
        ids = [p.unique_id for p in accepted]
        self.npcs.remove(np.flatnonzero(np.isin(self.npcs.unique_ids, ids)))
        self.npc_ghosts.place(accepted, self.sim_time)
        self._next_id = max([self._next_id, *(i + 1 for i in ids)])
        return [p.unique_id for p in placements if p.unique_id in taken]

    def add_object(
        self, model_name: str, position: tuple[float, float, float], heading: float
    ) -> int:
        """SyncModeAddObject: a new object of a catalogue model; its unique id.

        An obstacle model stands with its footprint centre at `position` (m), heading
        `heading` (rad); a vehicle model becomes an NPC at rest on the lane nearest to
        `position` (preferring lanes along `heading`), which then drives like any NPC.
        """
        unique_id = self._next_id
        if model_name in OBSTACLE_MODELS:
            obstacle = OBSTACLE_MODELS[model_name]
            size = (obstacle.length, obstacle.width, obstacle.height)
            self.obstacles.spawn([ObstacleSpawn(unique_id, model_name, position, heading, size)])
        elif model_name in VEHICLE_CATALOGUE:
            lane = self.map.project(position[0], position[1], heading)
            index = self.map.lane_index(lane.lane_id)
            vehicle = VEHICLE_CATALOGUE[model_name]
            self.npcs.spawn([NpcSpawn(unique_id, vehicle, index, lane.s, lane.lateral)])
        else:
            raise UnknownObjectModelError(model_name)
        self._next_id += 1
        return unique_id

    def remove_object(self, unique_id: int) -> bool:
        """SyncModeRemoveObject: take out the NPC or obstacle `unique_id`; False if none."""
        npc = np.flatnonzero(self.npcs.unique_ids == unique_id)
        if len(npc):
            self.npcs.remove(npc)
            return True
        return self.obstacles.remove(unique_id)

    # -- replay ------------------------------------------------------------------------

    def show_recorded(self, scene: RecordedScene) -> None:
        """Show `scene` from now on: its ego pose at once, its object tables instead of
        the world's own agents of those kinds, which stop being stepped until a later
        scene leaves their kind out (RecordedScene() returns to full simulation)."""
        self.recorded = scene
        recorded: tuple[tuple[ObjectTable | None, Callable[[ObjectTable], Population]], ...] = (
            (scene.npcs, RecordedVehicles),
            (scene.pedestrians, RecordedPedestrians),
            (scene.obstacles, RecordedObstacles),
        )
        kinds = tuple(
            own if table is None else (population(table),)
            for own, (table, population) in zip(self._own, recorded, strict=True)
        )
        if scene.ego is None:
            self._show(self._simulated_egos, kinds)
            return
        ego = scene.ego
        self.egos[0].vehicle.teleport(ego.pose, ego.speed, ego.front_steer, ego.rear_steer)
        self._show(ReplayedEgos(self._simulated_egos, ego), kinds)

    # -- stepping ----------------------------------------------------------------------

    def step(self, dt: float | None = None) -> None:
        """Advance dt s (default physics_step_s); a paused world does not move.

        The signals, then each population in order (the egos first; those a recording
        stands in for wait), then the contacts.
        """
        dt = self.physics_step_s if dt is None else dt
        if not dt > 0.0:
            raise ValueError(f"step needs a positive dt, got {dt}")
        if self.paused:
            return
        self.signals.step(dt)
        populations = self._populations
        surroundings = Surroundings(
            self.map, self._lights_view(), populations, self._egos, self._lane_memory
        )
        for population in populations:
            population.step(dt, surroundings)
        for waiting in self._waiting:
            waiting.wait(surroundings)
        self.sim_time += dt
        self._log(self._contacts.step(populations, self.contact_model, self.sim_time))

    def _lights_view(self) -> LightsView:
        """The signals as the agents read them, kept while no aspect changes (the same
        view, step after step: agents may keep what they work out from it)."""
        signals = self.signals
        known = self._lights
        if known is None or known[0] is not signals or known[1] != signals.changes:
            known = self._lights = (signals, signals.changes, LightsView.of(signals))
        return known[2]

    def _log(self, contacts: StepContacts) -> None:
        self.ego_contacts, self.vehicle_contacts = contacts.ego_contacts, contacts.vehicle_contacts
        for record in contacts.ego_collisions:
            self.ego_collisions[record.ego_id] = record
        self.ego_collision_log.extend(contacts.ego_collisions)
        self.vehicle_collisions.extend(contacts.vehicle_collisions)

    # -- scenarios ---------------------------------------------------------------------

    def load_scenario(
        self, scenario: Scenario, options: ScenarioLoadOptions | None = None
    ) -> ScenarioLoadReport:
        """ScenarioLoad (topic and service): apply `scenario` as its flags say.

        Everything is checked before anything changes: a ScenarioError (naming file, line
        and field) leaves the world as it was. Signals always take the scenario's
        programs (dropping overrides); the NPCs' random generator is reseeded.
        """
        options = options or ScenarioLoadOptions()
        check_map(scenario, self.map)
        scenario, notes = in_map_frame(scenario, self.map.georef)
        ids = self._allocate_ids()
        # Every section is checked, so that a file's mistakes are all reported at once.
        problems = Problems()
        signals = ego = None
        npcs: list[NpcSpawn] = []
        walkers: list[PedestrianSpawn] = []
        things: list[ObstacleSpawn] = []
        with problems.collecting():
            signals = self._signals_for(scenario)
        with problems.collecting():
            ego = ego_placement(scenario, self.map) if options.load_ego_vehicle_data else None
        with problems.collecting():
            if options.load_surrounding_vehicle_data:
                npcs = npc_spawns(scenario, self.map, ids)
        with problems.collecting():
            if options.load_pedestrian_data:
                walkers = pedestrian_spawns(scenario, self.map, ids)
        with problems.collecting():
            things = obstacle_spawns(scenario, ids) if options.load_object_data else []
        problems.raise_any()
        assert signals is not None

        self._next_id = next(ids)
        self.signals = signals
        if options.delete_all:
            self.npcs.clear()
            self.npc_ghosts.clear()
            self.pedestrians.clear()
            self.obstacles.clear()
            self.vehicle_collisions.clear()
            self.ego_collision_log.clear()
        self.npcs.rng = np.random.default_rng(scenario.seed)
        if ego is not None:
            model, pose, speed = ego
            main = self.egos[0]
            if main.vehicle.model != model:
                main.vehicle = ego_vehicle(model, pose, self._command_timeout_s)
            main.catalogue_model = model
            main.vehicle.teleport(pose, speed)
            if scenario.ego is not None and scenario.ego.gear is not None:
                main.vehicle.set_gear(scenario.ego.gear)
        self.npcs.spawn(npcs)
        self.pedestrians.spawn(walkers)
        self.obstacles.spawn(things)
        self.scripted.clear()
        self.scripted_egos.clear()
        self.storyboard = None
        if scenario.storyboard is not None:
            kinds = {
                "vehicle": options.load_surrounding_vehicle_data,
                "pedestrian": options.load_pedestrian_data,
                "miscellaneous object": options.load_object_data,
            }
            self.storyboard = scenario.storyboard.start(
                self,
                options.load_ego_vehicle_data,
                frozenset(kind for kind, wanted in kinds.items() if wanted),
                options.scenario_drives_ego,
            )
        self._contacts.forget(self.objects())
        self.ego_contacts, self.vehicle_contacts = {}, []
        self.paused = options.set_pause
        network = scenario.network if options.load_network_connection_data else None
        if options.load_network_connection_data:
            self.network_settings_request = network
        scripted = self.scripted
        return ScenarioLoadReport(
            ego_placed=ego is not None
            or bool(scenario.storyboard and options.load_ego_vehicle_data),
            npcs_spawned=len(npcs) + len(scripted.table(ObjectType.NPC_VEHICLE)),
            pedestrians_spawned=len(walkers) + len(scripted.table(ObjectType.PEDESTRIAN)),
            obstacles_spawned=len(things) + len(scripted.table(ObjectType.OBSTACLE)),
            network_settings=network,
            paused=self.paused,
            notes=notes,
        )

    def _signals_for(self, scenario: Scenario) -> TrafficSignals:
        spec = scenario.signals
        for intersection_id, path in spec.paths.items():
            if intersection_id not in self.map.intersections:
                raise scenario.error((*path, "id"), f"no intersection {intersection_id} in the map")
        programs = dict(spec.intersections)
        phase_paths = {i: (*path, "initial_phase") for i, path in spec.paths.items()}
        signalised = sorted(i for i, site in self.map.intersections.items() if site.light_ids)
        for start in spec.starts:
            if not 0 <= start.index < len(signalised):
                raise scenario.error(
                    start.path,
                    f"no signalised intersection number {start.index} in map "
                    f"{self.map.name!r} (it has {len(signalised)}, numbered from 0)",
                )
            intersection_id = signalised[start.index]
            programs[intersection_id] = IntersectionProgram(
                timing=spec.default, initial_phase=start.phase, initial_elapsed_s=start.elapsed_s
            )
            phase_paths[intersection_id] = start.path
        try:
            return TrafficSignals(self.map, programs, IntersectionProgram(timing=spec.default))
        except UnknownPhaseError as error:
            raise scenario.error(phase_paths[error.intersection_id], str(error)) from None


def _joined(tables: list[ObjectTable]) -> ObjectTable:
    """One table of `tables` in order (where only one has rows, that one as it is: most
    kinds have one population with agents in it)."""
    filled = [table for table in tables if len(table)]
    return filled[0] if len(filled) == 1 else ObjectTable.concatenate(filled or tables[:1])


__all__ = ["DEFAULT_PHYSICS_STEP_S", "Ego", "EgoLaneState", "ObjectState", "World"]
