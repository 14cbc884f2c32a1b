"""The World: map, ego vehicles, traffic, signals and collisions advanced by step(dt).

A thin assembly of the modules that hold the logic. It is pure and deterministic: the
same scenario, seed and command sequence give bit-identical states.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Iterator, Sequence
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from egosim.world.arrays import FloatArray, IntArray
from egosim.world.collision import (
    ContactTracker,
    EgoCollision,
    Footprints,
    VehicleCollision,
    touching_pairs,
)
from egosim.world.contact import Bodies, ContactModel, Response, respond
from egosim.world.map import LaneMap, LaneProjections
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
    OFF,
    RED,
    IntersectionProgram,
    LightState,
    TrafficSignals,
    UnknownPhaseError,
    governing_light_id,
)
from egosim.world.traffic import (
    CrosswalkLights,
    LaneGraph,
    LaneOccupants,
    LightsView,
    NpcFleet,
    ObjectState,
    ObjectTable,
    ObjectType,
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
from egosim.world.traffic.scripted import ScriptedObjects
from egosim.world.vehicle import (
    DEFAULT_EGO_MODEL,
    EgoModel,
    EgoVehicle,
    Pose,
    RoadSurface,
    VehicleStatus,
    ego_model,
    ego_vehicle,
)
from egosim.world.vehicle.catalogue import VEHICLE_CATALOGUE
from egosim.yamltext import Problems

DEFAULT_PHYSICS_STEP_S = 0.01
DEFAULT_OBJECT_LIST_SIZE = 20
# A pedestrian this close to a lane's edge (m) already counts as in the lane for drivers.
PEDESTRIAN_LANE_MARGIN_M = 1.0
PEDESTRIAN_HALF_DEPTH_M = 0.5
# Length of lane over which the grade under an ego is measured, m.
GRADE_BASE_M = 1.0
PEDESTRIAN_MASS_KG = 75.0


class UnknownObjectModelError(ValueError):
    """A model name that is neither an obstacle nor a vehicle of the catalogues."""

    def __init__(self, name: str) -> None:
        known = ", ".join(sorted([*OBSTACLE_MODELS, *VEHICLE_CATALOGUE]))
        super().__init__(f"unknown object model {name!r}; known: {known}")


class Ego:
    """One ego vehicle: its object id and the vehicle model that moves it."""

    def __init__(self, unique_id: int, vehicle: EgoVehicle) -> None:
        self.unique_id = unique_id
        self.vehicle = vehicle
        self.catalogue_model: EgoModel = vehicle.model
        """The catalogue model it was given (a scenario may drive it with the figures of
        its own car for a while: see use_model)."""

    def use_model(self, model: EgoModel, command_timeout: float | None) -> None:
        """Drive on as a vehicle of `model` (a scenario's car), where it is, as fast."""
        if self.vehicle.model == model:
            return
        status = self.vehicle.status()
        self.vehicle = ego_vehicle(model, status.pose, command_timeout)
        self.vehicle.teleport(status.pose, status.velocity[0])

    def box_centre(self, status: VehicleStatus) -> tuple[float, float]:
        """Footprint centre, m: the reference point moved to the middle of the body."""
        offset = self.vehicle.model.box_centre_ahead_of_reference
        yaw = status.pose.yaw
        return status.pose.x + offset * math.cos(yaw), status.pose.y + offset * math.sin(yaw)


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
        self._graph = LaneGraph(lane_map, self.signals.lane_signals.of_lane)
        self._crosswalk_lights = CrosswalkLights(crossed_lights(lane_map, self._light_positions()))
        self.npcs = NpcFleet(self._graph, np.random.default_rng(0))
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
        self._obstacle_occupants = LaneOccupants.empty()
        self._next_id = 1
        self._command_timeout_s: float | None = None
        self.egos: list[Ego] = []
        self.add_ego(DEFAULT_EGO_MODEL, self._first_lane_pose())
        self._contacts = ContactTracker()
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
        self.recorded = RecordedScene()
        """What a replay shows instead of simulating (nothing by default); see show_recorded."""
        self._footprints = self._current_footprints()
        self._ego_lane_cache: tuple[tuple[Pose, ...], LaneProjections] | None = None
        if scenario is not None:
            self.load_scenario(scenario)

    def _light_positions(self) -> dict[str, int]:
        return {light_id: k for k, light_id in enumerate(self.signals.light_ids)}

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
        status = self.egos[index].vehicle.status()
        recorded = self.recorded.ego
        if index > 0 or recorded is None:
            return status
        return replace(
            status,
            acceleration=recorded.acceleration,
            accel_pedal=recorded.accel_pedal,
            brake_pedal=recorded.brake_pedal,
        )

    def ego_lane_state(self, index: int = 0) -> EgoLaneState:
        projection = self._ego_lanes()[index]
        return EgoLaneState(
            lane_id=projection.lane_id,
            s=projection.s,
            lateral_offset=projection.lateral,
            distance_left=projection.distance_left,
            distance_right=projection.distance_right,
            cross_track_error=-projection.lateral,
        )

    def _ego_lanes(self) -> LaneProjections:
        """Where each ego's reference point lies on its lane (its yaw as the hint).

        Kept while no ego moves: the step, the ego status and the light lookup all ask,
        and each projection costs as much as stepping a vehicle.
        """
        poses = tuple(ego.vehicle.status().pose for ego in self.egos)
        known = self._ego_lane_cache
        if known is None or known[0] != poses:
            projection = self.map.project_many([(p.x, p.y) for p in poses], [p.yaw for p in poses])
            known = self._ego_lane_cache = (poses, projection)
        return known[1]

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

    def _ego_table(self) -> ObjectTable:
        rows = []
        for ego in self.egos:
            status = ego.vehicle.status()
            yaw = status.pose.yaw
            c, s = math.cos(yaw), math.sin(yaw)
            vx, vy, _ = status.velocity
            ax, ay, _ = status.acceleration
            x, y = ego.box_centre(status)
            model = ego.vehicle.model
            rows.append(
                (
                    ego.unique_id,
                    model.name,
                    (x, y, status.pose.z),
                    yaw,
                    (c * vx - s * vy, s * vx + c * vy, 0.0),
                    (c * ax - s * ay, s * ax + c * ay, 0.0),
                    (model.length, model.width, model.height),
                )
            )
        n = len(rows)
        return ObjectTable(
            unique_ids=np.array([r[0] for r in rows], dtype=np.int64),
            object_types=np.full(n, int(ObjectType.EGO), np.int64),
            names=tuple(r[1] for r in rows),
            positions=np.array([r[2] for r in rows], dtype=np.float64).reshape(-1, 3),
            headings=np.array([r[3] for r in rows], dtype=np.float64),
            velocities=np.array([r[4] for r in rows], dtype=np.float64).reshape(-1, 3),
            accelerations=np.array([r[5] for r in rows], dtype=np.float64).reshape(-1, 3),
            sizes=np.array([r[6] for r in rows], dtype=np.float64).reshape(-1, 3),
        )

    def shown_tables(self) -> list[ObjectTable]:
        """NPCs, pedestrians and obstacles in view: the recorded ones where a replay shows
        them, else the simulated ones."""
        recorded, scripted = self.recorded, self.scripted
        return [
            ObjectTable.concatenate(
                [self.npcs.table(), self.npc_ghosts.table(), scripted.table(ObjectType.NPC_VEHICLE)]
            )
            if recorded.npcs is None
            else recorded.npcs,
            ObjectTable.concatenate(
                [self.pedestrians.table(), scripted.table(ObjectType.PEDESTRIAN)]
            )
            if recorded.pedestrians is None
            else recorded.pedestrians,
            ObjectTable.concatenate([self.obstacles.table(), scripted.table(ObjectType.OBSTACLE)])
            if recorded.obstacles is None
            else recorded.obstacles,
        ]

    def objects(self) -> ObjectTable:
        """Every object: egos, then NPCs, pedestrians and obstacles."""
        return ObjectTable.concatenate([self._ego_table(), *self.shown_tables()])

    def object_list(self, ego_index: int = 0, size: int | None = None) -> ObjectList:
        """ObjectStatusList: counts of all spawned objects; the `size` (default
        object_list_size) objects closest to the ego, split by kind, closest first. The
        other egos count and appear among the vehicles.

        Closest is measured as a client measures it from the two messages: from the ego's
        reported position (its reference point, /Ego_topic's position) to each object's
        reported position (its footprint centre, ObjectStatus.position), in the plane.
        """
        npcs, pedestrians, obstacles = self.shown_tables()
        egos = self._ego_table()
        other_egos = egos.select(egos.unique_ids != self.egos[ego_index].unique_id)
        others = ObjectTable.concatenate([other_egos, npcs, pedestrians, obstacles])
        pose = self.ego_status(ego_index).pose
        return closest_objects(
            others,
            (pose.x, pose.y),
            self.object_list_size if size is None else size,
            counts=(len(other_egos) + len(npcs), len(pedestrians), len(obstacles)),
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
            self._place_obstacles_on_lanes()
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
        if self.obstacles.remove(unique_id):
            self._place_obstacles_on_lanes()
            return True
        return False

    # -- replay ------------------------------------------------------------------------

    def show_recorded(self, scene: RecordedScene) -> None:
        """Show `scene` from now on: its ego pose at once, its object tables instead of
        the simulated agents of those kinds, which stop being stepped until a later
        scene leaves their kind out (RecordedScene() returns to full simulation)."""
        self.recorded = scene
        if scene.ego is not None:
            ego = scene.ego
            self.egos[0].vehicle.teleport(ego.pose, ego.speed, ego.front_steer, ego.rear_steer)

    # -- stepping ----------------------------------------------------------------------

    def step(self, dt: float | None = None) -> None:
        """Advance dt s (default physics_step_s); a paused world does not move."""
        dt = self.physics_step_s if dt is None else dt
        if not dt > 0.0:
            raise ValueError(f"step needs a positive dt, got {dt}")
        if self.paused:
            return
        self.signals.step(dt)
        recorded = self.recorded
        surfaces = self._road_surfaces()
        for index, ego in enumerate(self.egos):
            # A replayed main ego holds the recorded pose show_recorded gave it, and a
            # storyboard places the egos it drives.
            if (index > 0 or recorded.ego is None) and ego.unique_id not in self.scripted_egos:
                ego.vehicle.step(dt, surfaces[index])
        lights = LightsView.of(self.signals)
        egos, walkers = self._lane_users()
        self._wake_dormant()
        others = LaneOccupants.concatenate(
            [
                egos,
                self.npc_ghosts.occupants(self.map),
                self.scripted.occupants(self.map),
                walkers,
                self._obstacle_occupants,
            ]
        )
        if recorded.npcs is None:
            self.npcs.step(dt, lights, others)
        if recorded.pedestrians is None:
            stops_traffic = (lights.aspects == RED) | (lights.aspects == OFF) | lights.flashing
            self.pedestrians.step(dt, self._crosswalk_lights.walk_signals(stops_traffic))
        if recorded.obstacles is None and self.obstacles.step(dt):
            self._place_obstacles_on_lanes()
        self.sim_time += dt
        self._collide()

    def _wake_dormant(self) -> None:
        """NPCs and pedestrians waiting for an ego to come near set off when one has."""
        if not (self.npcs.dormant.any() or self.pedestrians.dormant.any()):
            return
        poses = [ego.vehicle.status().pose for ego in self.egos]
        points = np.array([(pose.x, pose.y) for pose in poses], dtype=np.float64)
        self.npcs.wake(points)
        self.pedestrians.wake(points)

    def _road_surfaces(self) -> list[RoadSurface]:
        """The road under each ego: the height of its lane there, and the pitch the
        lane's grade gives a vehicle facing the ego's way (roll: none)."""
        projection = self._ego_lanes()
        n = len(projection)
        yaws = np.array([ego.vehicle.status().pose.yaw for ego in self.egos])
        stations = np.concatenate(
            (projection.s, projection.s - GRADE_BASE_M / 2.0, projection.s + GRADE_BASE_M / 2.0)
        )
        poses = self.map.poses_at(np.tile(projection.lane_index, 3), stations)
        here, below, above = poses[:n], poses[n : 2 * n], poses[2 * n :]
        run = np.maximum(np.hypot(*(above[:, :2] - below[:, :2]).T), 1e-9)
        grade = (above[:, 2] - below[:, 2]) / run * np.cos(yaws - projection.heading)
        return [
            RoadSurface(z=float(z), pitch=float(-np.arctan(g)))
            for z, g in zip(here[:, 2], grade, strict=True)
        ]

    def _lane_users(self) -> tuple[LaneOccupants, LaneOccupants]:
        """The egos and the pedestrians in lanes, for the drivers behind them.

        One projection serves both, and keeps the egos' reference points for the next
        step's road surfaces and for the ego status (see _ego_lanes).
        """
        statuses = [ego.vehicle.status() for ego in self.egos]
        n = len(statuses)
        references = [(s.pose.x, s.pose.y) for s in statuses]
        centres = [ego.box_centre(s) for ego, s in zip(self.egos, statuses, strict=True)]
        yaws = np.array([s.pose.yaw for s in statuses])
        walkers = self._walkers_on_road()
        projection = self.map.project_many(
            np.concatenate((np.array(references + centres), walkers)).reshape(-1, 2),
            np.concatenate((yaws, yaws, np.full(len(walkers), np.nan))),
        )
        self._ego_lane_cache = (tuple(s.pose for s in statuses), projection.part(0, n))
        return (
            self._ego_occupants(statuses, projection.part(n, 2 * n)),
            self._pedestrian_occupants(projection.part(2 * n, len(projection))),
        )

    def _ego_occupants(
        self, statuses: list[VehicleStatus], centres: LaneProjections
    ) -> LaneOccupants:
        yaws = np.array([s.pose.yaw for s in statuses])
        widths = np.array([ego.vehicle.model.width for ego in self.egos])
        on_lane = np.abs(centres.lateral) <= (centres.width + widths) / 2.0
        lengths = np.array([ego.vehicle.model.length for ego in self.egos])
        along = np.cos(yaws - centres.heading) * np.array([s.velocity[0] for s in statuses])
        return LaneOccupants(
            centres.lane_index[on_lane],
            centres.s[on_lane],
            lengths[on_lane] / 2.0,
            along[on_lane],
        )

    def _walkers_on_road(self) -> FloatArray:
        """(N, 2) positions of the pedestrians who may stand in a lane."""
        recorded = self.recorded.pedestrians
        if recorded is None:
            # Sidewalk walkers never leave the kerb: only the others can be in a lane.
            return self.pedestrians.position[self.pedestrians.on_road]
        return recorded.positions[:, :2]

    @staticmethod
    def _pedestrian_occupants(walkers: LaneProjections) -> LaneOccupants:
        near = np.abs(walkers.lateral) <= walkers.width / 2.0 + PEDESTRIAN_LANE_MARGIN_M
        count = int(np.count_nonzero(near))
        return LaneOccupants(
            walkers.lane_index[near],
            walkers.s[near],
            np.full(count, PEDESTRIAN_HALF_DEPTH_M),
            np.zeros(count),
        )

    def _place_obstacles_on_lanes(self) -> None:
        table = self.obstacles.table()
        if len(table) == 0:
            self._obstacle_occupants = LaneOccupants.empty()
            return
        projection = self.map.project_many(table.positions[:, :2])
        reach = np.hypot(table.sizes[:, 0], table.sizes[:, 1]) / 2.0
        on_lane = np.abs(projection.lateral) <= projection.width / 2.0 + reach
        self._obstacle_occupants = LaneOccupants(
            projection.lane_index[on_lane],
            projection.s[on_lane],
            reach[on_lane],
            np.zeros(int(np.count_nonzero(on_lane))),
        )

    def _current_footprints(self, table: ObjectTable | None = None) -> Footprints:
        table = self.objects() if table is None else table
        return Footprints(
            table.positions[:, :2].copy(),
            table.headings.copy(),
            table.sizes[:, 0].copy(),
            table.sizes[:, 1].copy(),
        )

    def _collide(self) -> None:
        """Record the contacts that began this step and answer every contact physically.

        Ego against anything: a CollisionData record. NPC against NPC: a VehicleCollision
        record. A struck NPC brakes to a standstill and stays (crashed); a struck
        pedestrian stops. Every contact with a vehicle in it gets the response of
        world/contact.py (see _bodies for who is movable); pedestrians pass each other.
        """
        table = self.objects()
        now = self._current_footprints(table)
        before = self._footprints if len(self._footprints.headings) == len(table) else now
        self._footprints = now
        pairs = touching_pairs(before, now)
        self.ego_contacts, self.vehicle_contacts = {}, []
        if len(pairs) == 0:
            self._contacts.begin([], self.sim_time)
            return
        kinds = table.object_types[pairs]
        vehicles = (kinds == ObjectType.EGO) | (kinds == ObjectType.NPC_VEHICLE)
        self._record_contacts(table, pairs, kinds)
        bodies = self._bodies(table, now)
        response = respond(bodies, pairs[np.any(vehicles, axis=1)], self.contact_model)
        if response.moved.any():
            self._apply(response, bodies)
            # Contacts move bodies, never turn them: the next sweep starts from here.
            self._footprints = replace(now, centres=now.centres + response.displacements)

    def _record_contacts(self, table: ObjectTable, pairs: IntArray, kinds: IntArray) -> None:
        ego_pair = np.any(kinds == ObjectType.EGO, axis=1)
        npc_pair = np.all(kinds == ObjectType.NPC_VEHICLE, axis=1)
        relevant = pairs[ego_pair | npc_pair]
        ids = table.unique_ids
        rows = {(int(ids[i]), int(ids[j])): (int(i), int(j)) for i, j in relevant}
        touching = list(rows)
        fresh = self._contacts.begin(touching, self.sim_time)
        for pair, (i, j) in rows.items():
            records = (table.record(i), table.record(j))
            for me, other in (records, records[::-1]):
                if me.object_type == ObjectType.EGO:
                    self.ego_contacts.setdefault(me.unique_id, []).append(other)
            if not any(r.object_type == ObjectType.EGO for r in records):
                began = self._contacts.began_at.get(pair, self.sim_time)
                self.vehicle_contacts.append(VehicleCollision(began, records))
        if not fresh:
            return
        # Only simulated agents can be halted; recorded ones go where the recording says.
        npcs: IntArray | list[int] = self.npcs.unique_ids if self.recorded.npcs is None else []
        walkers: IntArray | list[int] = (
            self.pedestrians.unique_ids if self.recorded.pedestrians is None else []
        )
        npc_slot = {int(uid): k for k, uid in enumerate(npcs)}
        walker_slot = {int(uid): k for k, uid in enumerate(walkers)}
        for pair in fresh:
            i, j = rows[pair]
            records = (table.record(i), table.record(j))
            if not any(r.object_type == ObjectType.EGO for r in records):
                self.vehicle_collisions.append(VehicleCollision(self.sim_time, records))
            for me, other in (records, records[::-1]):
                if me.object_type == ObjectType.EGO:
                    record = EgoCollision(self.sim_time, me.unique_id, other)
                    self.ego_collisions[me.unique_id] = record
                    self.ego_collision_log.append(record)
                elif me.object_type == ObjectType.NPC_VEHICLE and me.unique_id in npc_slot:
                    self.npcs.stop([npc_slot[me.unique_id]])
                elif me.object_type == ObjectType.PEDESTRIAN and me.unique_id in walker_slot:
                    self.pedestrians.stop([walker_slot[me.unique_id]])

    def _bodies(self, table: ObjectTable, footprints: Footprints) -> Bodies:
        """The objects of `table` (the order of objects()) as contact bodies.

        Movable, with their mass: simulated egos, moving NPCs, pedestrians, light obstacles
        (cones, drums, boxes). Immovable: barriers, parked NPCs (still waiting to set
        off), NPC ghosts and whatever a replay shows (its motion is dictated).
        """
        recorded = self.recorded
        ego_mass = [ego.vehicle.model.mass for ego in self.egos]
        ego_inverse = 1.0 / np.array(ego_mass)
        if recorded.ego is not None:
            ego_inverse[0] = 0.0
        for k, ego in enumerate(self.egos):
            if ego.unique_id in self.scripted_egos:
                ego_inverse[k] = 0.0
        # Scripted objects keep 0: the storyboard dictates their motion.
        others = np.zeros(len(table) - len(self.egos))
        if recorded.npcs is None:
            others[: len(self.npcs)] = np.where(self.npcs.parked(), 0.0, 1.0 / self.npcs.mass)
        start = self._shown_npc_count()
        if recorded.pedestrians is None:
            others[start : start + len(self.pedestrians)] = 1.0 / PEDESTRIAN_MASS_KG
        if recorded.obstacles is None:
            first = self._first_obstacle_row() - len(self.egos)
            others[first : first + len(self.obstacles)] = self.obstacles.inverse_masses()
        return Bodies(footprints, table.velocities[:, :2], np.concatenate((ego_inverse, others)))

    def _shown_npc_count(self) -> int:
        """Rows of vehicles in objects() after the egos: simulated NPCs and ghosts, or the
        replayed ones."""
        recorded = self.recorded.npcs
        if recorded is not None:
            return len(recorded)
        return (
            len(self.npcs) + len(self.npc_ghosts) + len(self.scripted.table(ObjectType.NPC_VEHICLE))
        )

    def _first_obstacle_row(self) -> int:
        """Row in objects() of the first obstacle: after the egos, vehicles, pedestrians."""
        recorded = self.recorded.pedestrians
        walkers = (
            len(self.pedestrians) + len(self.scripted.table(ObjectType.PEDESTRIAN))
            if recorded is None
            else len(recorded)
        )
        return len(self.egos) + self._shown_npc_count() + walkers

    def _apply(self, response: Response, bodies: Bodies) -> None:
        """Hand each moved simulated body its share of the response."""
        moved = response.moved
        displacement, velocity = response.displacements, response.velocities
        change = velocity - bodies.velocities
        for k, ego in enumerate(self.egos):
            if moved[k] and ego.unique_id not in self.scripted_egos:
                ego.vehicle.shove(tuple(displacement[k]), tuple(change[k]))
        start = len(self.egos)
        if self.recorded.npcs is None:
            rows = np.flatnonzero(moved[start : start + len(self.npcs)])
            if rows.size:
                self.npcs.shove(rows, displacement[start + rows], velocity[start + rows])
        start += self._shown_npc_count()
        if self.recorded.pedestrians is None:
            rows = np.flatnonzero(moved[start : start + len(self.pedestrians)])
            if rows.size:
                self.pedestrians.shove(rows, displacement[start + rows])
        if self.recorded.obstacles is None:
            start = self._first_obstacle_row()
            rows = np.flatnonzero(moved[start : start + len(self.obstacles)])
            if rows.size:
                self.obstacles.shove(rows, displacement[start + rows], velocity[start + rows])
                self._place_obstacles_on_lanes()

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
        self._place_obstacles_on_lanes()
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
        self._contacts.clear()
        self.ego_contacts, self.vehicle_contacts = {}, []
        self._footprints = self._current_footprints()
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


__all__ = ["DEFAULT_PHYSICS_STEP_S", "Ego", "EgoLaneState", "ObjectState", "World"]
