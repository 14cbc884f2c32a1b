"""The World: map, ego vehicles, traffic, signals and collisions advanced by step(dt).

A thin assembly of the modules that hold the logic. Its agents are populations
(world/populations): the egos, then the NPC vehicles (simulated and ghosts), the
pedestrians and the obstacles, in the order of the object table; a replay swaps a
recorded population in for a kind's simulated ones. The world orders them, steps them
and keeps the logs; world/contact_handling.py answers their contacts. It is pure and
deterministic: the same scenario, seed and command sequence give bit-identical states.
"""

from __future__ import annotations

import itertools
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from egosim.world.collision import EgoCollision, VehicleCollision
from egosim.world.contact import ContactModel
from egosim.world.contact_handling import ContactHandler, StepContacts
from egosim.world.map import LaneMap
from egosim.world.populations import (
    Ego,
    EgoPopulation,
    PlacedGhosts,
    Population,
    RecordedObstacles,
    RecordedPedestrians,
    RecordedVehicles,
    ReplayedEgos,
    SimulatedEgos,
    SimulatedNpcs,
    SimulatedObstacles,
    SimulatedPedestrians,
    Surroundings,
)
from egosim.world.recorded_scene import RecordedScene
from egosim.world.scenario import Scenario, ScenarioLoadOptions, ScenarioLoadReport
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
    NpcFleet,
    ObjectState,
    ObjectTable,
    PedestrianCrowd,
    StaticObstacles,
    closest_objects,
    crossed_lights,
)
from egosim.world.traffic.catalogue import OBSTACLE_MODELS
from egosim.world.traffic.ghosts import GhostPlacement, NpcGhosts
from egosim.world.traffic.npc_vehicles import NpcSpawn
from egosim.world.traffic.object_list import ObjectList
from egosim.world.traffic.obstacles import ObstacleSpawn
from egosim.world.traffic.pedestrians import PedestrianSpawn
from egosim.world.vehicle import (
    DEFAULT_EGO_MODEL,
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
        graph = LaneGraph(lane_map, self.signals.light_ids)
        light_positions = {light_id: k for k, light_id in enumerate(self.signals.light_ids)}
        self.npcs = NpcFleet(graph, np.random.default_rng(0))
        self.npc_ghosts = NpcGhosts()
        self.pedestrians = PedestrianCrowd()
        self.obstacles = StaticObstacles()
        self._next_id = 1
        self._command_timeout_s: float | None = None
        self.egos: list[Ego] = []
        self._simulated_egos = SimulatedEgos(lane_map, self.egos)
        self._simulated: tuple[tuple[Population, ...], ...] = (
            (SimulatedNpcs(self.npcs), PlacedGhosts(self.npc_ghosts)),
            (
                SimulatedPedestrians(
                    self.pedestrians, CrosswalkLights(crossed_lights(lane_map, light_positions))
                ),
            ),
            (SimulatedObstacles(self.obstacles, lane_map),),
        )
        """Per kind (NPC vehicles, pedestrians, obstacles): its simulated populations."""
        self.recorded = RecordedScene()
        """What a replay shows instead of simulating (nothing by default); see show_recorded."""
        self._show(self._simulated_egos, self._simulated)
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
        self.network_settings_request: dict[str, Any] | None = None
        """The network settings of the last ScenarioLoad that asked for them."""
        self._contacts = ContactHandler(self.objects())
        if scenario is not None:
            self.load_scenario(scenario)

    def _first_lane_pose(self) -> Pose:
        x, y, z, heading = self.map.pose_at(self.map.lane_ids[0], 0.0)
        return Pose(x=x, y=y, z=z, yaw=heading)

    def _allocate_ids(self) -> Iterator[int]:
        return itertools.count(self._next_id)

    def _show(self, egos: EgoPopulation, kinds: tuple[tuple[Population, ...], ...]) -> None:
        """From now on the world's agents are `egos`, then the populations of each kind."""
        self._egos = egos
        self._kinds = kinds
        self._populations: tuple[Population, ...] = (egos, *itertools.chain(*kinds))

    # -- egos ------------------------------------------------------------------------

    def add_ego(self, model_name: str, pose: Pose) -> Ego:
        """A further ego vehicle (the first one is the main ego)."""
        vehicle = ego_vehicle(ego_model(model_name), pose, self._command_timeout_s)
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
        them, else the simulated ones."""
        return [_joined([population.table() for population in kind]) for kind in self._kinds]

    def objects(self) -> ObjectTable:
        """Every object: egos, then NPCs, pedestrians and obstacles."""
        return ObjectTable.concatenate([population.table() for population in self._populations])

    def object_list(self, ego_index: int = 0, size: int | None = None) -> ObjectList:
        """ObjectStatusList: counts of all spawned objects; the `size` (default
        object_list_size) objects closest to the ego, split by kind, closest first. The
        other egos count and appear among the vehicles."""
        npcs, pedestrians, obstacles = self.shown_tables()
        egos = self._egos.table()
        other_egos = egos.select(egos.unique_ids != self.egos[ego_index].unique_id)
        others = ObjectTable.concatenate([other_egos, npcs, pedestrians, obstacles])
        status = self.ego_status(ego_index)
        centre = self.egos[ego_index].box_centre(status)
        return closest_objects(
            others,
            centre,
            self.object_list_size if size is None else size,
            counts=(len(other_egos) + len(npcs), len(pedestrians), len(obstacles)),
        )

    def place_npc_ghosts(self, placements: Sequence[GhostPlacement]) -> list[int]:
        """NpcGhostCmd: each placed NPC leaves the simulation and stands where it is told;
        an unknown id becomes a new NPC. Returns the ids refused: those of an ego, a
        pedestrian or an obstacle."""
        taken = {ego.unique_id for ego in self.egos}
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
        the simulated agents of those kinds, which stop being stepped until a later
        scene leaves their kind out (RecordedScene() returns to full simulation)."""
        self.recorded = scene
        recorded: tuple[tuple[ObjectTable | None, Callable[[ObjectTable], Population]], ...] = (
            (scene.npcs, RecordedVehicles),
            (scene.pedestrians, RecordedPedestrians),
            (scene.obstacles, RecordedObstacles),
        )
        kinds = tuple(
            simulated if table is None else (population(table),)
            for simulated, (table, population) in zip(self._simulated, recorded, strict=True)
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

        The signals, then each population in order (the egos first), then the contacts.
        """
        dt = self.physics_step_s if dt is None else dt
        if not dt > 0.0:
            raise ValueError(f"step needs a positive dt, got {dt}")
        if self.paused:
            return
        self.signals.step(dt)
        populations = self._populations
        surroundings = Surroundings(self.map, LightsView.of(self.signals), populations)
        for population in populations:
            population.step(dt, surroundings)
        self.sim_time += dt
        self._log(self._contacts.step(populations, self.contact_model, self.sim_time))

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
            main.vehicle.teleport(pose, speed)
        self.npcs.spawn(npcs)
        self.pedestrians.spawn(walkers)
        self.obstacles.spawn(things)
        self._contacts.forget(self.objects())
        self.ego_contacts, self.vehicle_contacts = {}, []
        self.paused = options.set_pause
        network = scenario.network if options.load_network_connection_data else None
        if options.load_network_connection_data:
            self.network_settings_request = network
        return ScenarioLoadReport(
            ego_placed=ego is not None,
            npcs_spawned=len(npcs),
            pedestrians_spawned=len(walkers),
            obstacles_spawned=len(things),
            network_settings=network,
            paused=self.paused,
        )

    def _signals_for(self, scenario: Scenario) -> TrafficSignals:
        spec = scenario.signals
        for intersection_id, path in spec.paths.items():
            if intersection_id not in self.map.intersections:
                raise scenario.error((*path, "id"), f"no intersection {intersection_id} in the map")
        try:
            return TrafficSignals(
                self.map, spec.intersections, IntersectionProgram(timing=spec.default)
            )
        except UnknownPhaseError as error:
            path = spec.paths[error.intersection_id]
            raise scenario.error((*path, "initial_phase"), str(error)) from None


def _joined(tables: list[ObjectTable]) -> ObjectTable:
    """One table of `tables` in order (a kind's single population's own table as it is)."""
    return tables[0] if len(tables) == 1 else ObjectTable.concatenate(tables)


__all__ = ["DEFAULT_PHYSICS_STEP_S", "Ego", "EgoLaneState", "ObjectState", "World"]
