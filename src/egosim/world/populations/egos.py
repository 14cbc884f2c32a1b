"""The ego vehicles as a population: driven by their commands or placed by a storyboard,
or the main one replayed."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from egosim.world.arrays import FloatArray, IntArray
from egosim.world.collision import Footprints
from egosim.world.map import LaneMap, LaneProjections
from egosim.world.populations.base import LanePoints, Shove, Surroundings
from egosim.world.recorded_scene import RecordedEgo
from egosim.world.traffic import LaneOccupants, ObjectTable, ObjectType
from egosim.world.vehicle import (
    EgoModel,
    EgoVehicle,
    Motion,
    Pose,
    RoadSurface,
    VehicleStatus,
    ego_vehicle,
)

GRADE_BASE_M = 1.0
"""Length of lane over which the grade under an ego is measured, m."""


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

    def box_centre(self, motion: Motion | VehicleStatus) -> tuple[float, float]:
        """Footprint centre, m: the reference point moved to the middle of the body."""
        offset = self.vehicle.model.box_centre_ahead_of_reference
        yaw = motion.pose.yaw
        return motion.pose.x + offset * math.cos(yaw), motion.pose.y + offset * math.sin(yaw)


class SimulatedEgos:
    """Every ego driven by its own commands, on the road under it, except those whose
    pose a storyboard places (`scripted`, by unique id): those are not stepped and are
    immovable in a contact.

    `egos` and `scripted` are the world's own list and set: what is added to or removed
    from them is the population's at once.
    """

    def __init__(self, lane_map: LaneMap, egos: list[Ego], scripted: set[int]) -> None:
        self.map = lane_map
        self.egos = egos
        self.scripted = scripted
        self._lane_cache: tuple[tuple[Pose, ...], LaneProjections] | None = None
        self._surface_cache: tuple[tuple[Pose, ...], list[RoadSurface]] | None = None
        self._placed: (
            tuple[tuple[tuple[Pose, EgoModel], ...], tuple[LanePoints, Footprints]] | None
        ) = None

    def status(self, index: int) -> VehicleStatus:
        return self.egos[index].vehicle.status()

    def positions(self) -> FloatArray:
        poses = [ego.vehicle.motion().pose for ego in self.egos]
        return np.array([(pose.x, pose.y) for pose in poses], dtype=np.float64)

    def lanes(self) -> LaneProjections:
        """Kept while no ego moves: the step, the ego status and the light lookup all
        ask, and each projection costs as much as stepping a vehicle."""
        poses = tuple(ego.vehicle.motion().pose for ego in self.egos)
        known = self._lane_cache
        if known is None or known[0] != poses:
            projection = self.map.project_many([(p.x, p.y) for p in poses], [p.yaw for p in poses])
            known = self._lane_cache = (poses, projection)
        elif len(known[1]) != len(poses):
            # lane_occupants keeps the step's whole projection: the egos' part is cut out
            # only when someone asks.
            known = self._lane_cache = (poses, known[1].part(0, len(poses)))
        return known[1]

    def table(self) -> ObjectTable:
        rows = []
        for ego in self.egos:
            motion = ego.vehicle.motion()
            yaw = motion.pose.yaw
            c, s = math.cos(yaw), math.sin(yaw)
            vx, vy, _ = motion.velocity
            ax, ay, _ = motion.acceleration
            x, y = ego.box_centre(motion)
            model = ego.vehicle.model
            rows.append(
                (
                    *(x, y, motion.pose.z),
                    yaw,
                    *(c * vx - s * vy, s * vx + c * vy, 0.0),  # velocity, map frame
                    *(c * ax - s * ay, s * ax + c * ay, 0.0),  # acceleration
                    *(model.length, model.width, model.height),
                )
            )
        n = len(rows)
        # One array for every column: a step asks for this table, each call counts.
        values = np.array(rows, dtype=np.float64).reshape(n, 13)
        return ObjectTable(
            unique_ids=np.array([ego.unique_id for ego in self.egos], dtype=np.int64),
            object_types=np.full(n, int(ObjectType.EGO), np.int64),
            names=tuple(ego.vehicle.model.name for ego in self.egos),
            positions=values[:, 0:3],
            headings=values[:, 3],
            velocities=values[:, 4:7],
            accelerations=values[:, 7:10],
            sizes=values[:, 10:13],
        )

    def footprints(self) -> Footprints:
        return self._placement()[1]

    def lane_points(self) -> LanePoints:
        """Each ego's reference point, then each one's footprint centre, its yaw as hint:
        the first give the lanes (kept, see lanes), the second the lane occupants."""
        return self._placement()[0]

    def _placement(self) -> tuple[LanePoints, Footprints]:
        """The egos' lane points and footprints, worked out together and kept while no
        ego moves (or changes its model)."""
        motions = [ego.vehicle.motion() for ego in self.egos]
        key = tuple(
            (motion.pose, ego.vehicle.model) for ego, motion in zip(self.egos, motions, strict=True)
        )
        known = self._placed
        if known is not None and known[0] == key:
            return known[1]
        rows = []
        for ego, motion in zip(self.egos, motions, strict=True):
            model = ego.vehicle.model
            pose = motion.pose
            centre = ego.box_centre(motion)
            rows.append((pose.x, pose.y, *centre, pose.yaw, model.length, model.width))
        values = np.array(rows, dtype=np.float64).reshape(len(rows), 7)
        yaws = values[:, 4]
        placement = (
            LanePoints(
                np.concatenate((values[:, 0:2], values[:, 2:4])), np.concatenate((yaws, yaws))
            ),
            Footprints(values[:, 2:4], yaws, values[:, 5], values[:, 6]),
        )
        self._placed = (key, placement)
        return placement

    def lane_occupants(self, placed: LaneProjections) -> LaneOccupants:
        motions = [ego.vehicle.motion() for ego in self.egos]
        n = len(motions)
        self._lane_cache = (tuple(m.pose for m in motions), placed)
        # Ego by ego in floats: a world has a few egos, and a numpy call on so few
        # values costs more than the arithmetic.
        lanes: list[int] = []
        rows: list[tuple[float, float, float]] = []
        for k, (ego, motion) in enumerate(zip(self.egos, motions, strict=True)):
            model = ego.vehicle.model
            row = n + k
            if abs(placed.lateral.item(row)) <= (placed.width.item(row) + model.width) / 2.0:
                along = math.cos(motion.pose.yaw - placed.heading.item(row)) * motion.velocity[0]
                lanes.append(placed.lane_index.item(row))
                rows.append((placed.s.item(row), model.length / 2.0, along))
        if not lanes:
            return LaneOccupants.empty()
        values = np.array(rows, dtype=np.float64)
        return LaneOccupants(np.array(lanes, np.int64), values[:, 0], values[:, 1], values[:, 2])

    def inverse_masses(self) -> FloatArray:
        inverse: FloatArray = 1.0 / np.array([ego.vehicle.model.mass for ego in self.egos])
        if self.scripted:
            placed = np.array([ego.unique_id in self.scripted for ego in self.egos], dtype=bool)
            inverse[placed] = 0.0
        return inverse

    def step(self, dt: float, surroundings: Surroundings) -> None:
        self.drive(dt)

    def drive(self, dt: float, first: int = 0) -> None:
        """Step the egos from index `first` on, each on the road under it (those a
        storyboard places stay where it put them)."""
        surfaces = self.road_surfaces()
        for ego, surface in zip(self.egos[first:], surfaces[first:], strict=True):
            if ego.unique_id not in self.scripted:
                ego.vehicle.step(dt, surface)

    def road_surfaces(self) -> list[RoadSurface]:
        """The road under each ego: the height of its lane there, and the pitch the
        lane's grade gives a vehicle facing the ego's way (roll: none). Kept, like the
        lanes, while no ego moves (an ego at rest asks for the same road every step)."""
        poses = tuple(ego.vehicle.motion().pose for ego in self.egos)
        known = self._surface_cache
        if known is None or known[0] != poses:
            known = self._surface_cache = (poses, self._road_surfaces())
        return known[1]

    def _road_surfaces(self) -> list[RoadSurface]:
        projection = self.lanes()
        n = len(projection)
        yaws = np.array([ego.vehicle.motion().pose.yaw for ego in self.egos])
        stations = np.concatenate(
            (projection.s, projection.s - GRADE_BASE_M / 2.0, projection.s + GRADE_BASE_M / 2.0)
        )
        lanes = projection.lane_index
        poses = self.map.poses_at(np.concatenate((lanes, lanes, lanes)), stations)
        here, below, above = poses[:n], poses[n : 2 * n], poses[2 * n :]
        run = np.maximum(np.hypot(*(above[:, :2] - below[:, :2]).T), 1e-9)
        grade = (above[:, 2] - below[:, 2]) / run * np.cos(yaws - projection.heading)
        return [
            RoadSurface(z=float(z), pitch=float(-np.arctan(g)))
            for z, g in zip(here[:, 2], grade, strict=True)
        ]

    def shove(self, shove: Shove) -> None:
        for row, displacement, change in zip(
            shove.rows.tolist(), shove.displacements, shove.velocity_changes, strict=True
        ):
            ego = self.egos[row]
            if ego.unique_id not in self.scripted:
                ego.vehicle.shove(tuple(displacement), tuple(change))

    def halt(self, rows: IntArray) -> None:
        """An ego's driver decides for itself what to do after a collision."""


class ReplayedEgos:
    """The main ego where a recording puts it (World.show_recorded places it), held there
    and immovable in a contact, reporting the recorded acceleration and pedals; the other
    egos simulated as ever."""

    def __init__(self, simulated: SimulatedEgos, recorded: RecordedEgo) -> None:
        self.simulated = simulated
        self.recorded = recorded

    def status(self, index: int) -> VehicleStatus:
        status = self.simulated.status(index)
        if index > 0:
            return status
        recorded = self.recorded
        return replace(
            status,
            acceleration=recorded.acceleration,
            accel_pedal=recorded.accel_pedal,
            brake_pedal=recorded.brake_pedal,
        )

    def lanes(self) -> LaneProjections:
        return self.simulated.lanes()

    def positions(self) -> FloatArray:
        return self.simulated.positions()

    def table(self) -> ObjectTable:
        return self.simulated.table()

    def footprints(self) -> Footprints:
        return self.simulated.footprints()

    def lane_points(self) -> LanePoints:
        return self.simulated.lane_points()

    def lane_occupants(self, placed: LaneProjections) -> LaneOccupants:
        return self.simulated.lane_occupants(placed)

    def inverse_masses(self) -> FloatArray:
        inverse = self.simulated.inverse_masses()
        inverse[0] = 0.0
        return inverse

    def step(self, dt: float, surroundings: Surroundings) -> None:
        self.simulated.drive(dt, first=1)

    def shove(self, shove: Shove) -> None:
        self.simulated.shove(shove)

    def halt(self, rows: IntArray) -> None:
        self.simulated.halt(rows)
