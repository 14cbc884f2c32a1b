"""The ego's autopilot (MORAI's internal controller, EventInfo ctrl_mode 4), kept simple.

It follows the lane the vehicle is on and the lanes after it (the straightest successor
at each fork) with pure-pursuit steering. Longitudinally it asks, in velocity mode, for
the speed the NPCs drive at (the lane's limit capped by its comfortable curve speed,
slowing in time for the next lane's), and for less where it must: behind the nearest
road user on its planned lanes, before a stop line whose light says stop (a yellow
judged once per approach, as the NPCs do) and before a dead end. Each of these is a
comfortable braking curve towards a point short of the obstacle.
"""

from __future__ import annotations

import math

import numpy as np

from egosim.world.map import Lane
from egosim.world.traffic.idm import IntelligentDriverModel
from egosim.world.traffic.lane_graph import TURN_STRAIGHT, LaneGraph
from egosim.world.traffic.leaders import LaneOccupants
from egosim.world.traffic.signal_rules import LightsView, signal_permissions
from egosim.world.vehicle import ControlCommand, LongitudinalMode, VehicleModel, VehicleStatus
from egosim.world.vehicle.pedal_control import SPEED_GAIN

LOOKAHEAD_MIN_M = 5.0
LOOKAHEAD_TIME_S = 0.6
"""Pure-pursuit look-ahead: this many seconds of travel, at least LOOKAHEAD_MIN_M."""
PLANNED_LANES = 3
"""The current lane and the lanes after it the autopilot keeps planned."""
STOP_MARGIN_M = 1.5
"""The front bumper comes to rest this far before a stop line or a dead end."""
STOP_PREVIEW_S = 1.0 / SPEED_GAIN
"""The velocity loop trails a falling target by about its time constant: the braking
target is the one for where the vehicle will be that much later."""
ON_LANE_MARGIN_M = 1.0
"""How far outside its planned lane's edge the vehicle may be and still count as on it."""

_YELLOW_UNDECIDED, _YELLOW_STOP, _YELLOW_PASS = 0, 1, 2


class LaneAutopilot:
    """Drives one vehicle: command(...) once per step gives the ControlCommand to apply."""

    def __init__(self, graph: LaneGraph, idm: IntelligentDriverModel | None = None) -> None:
        self.graph = graph
        self.idm = idm or IntelligentDriverModel()
        self.path: list[int] = []
        """Lane indices: the lane the vehicle is on, then the ones it will take."""
        self._yellow = _YELLOW_UNDECIDED

    def command(
        self,
        model: VehicleModel,
        status: VehicleStatus,
        lights: LightsView,
        others: LaneOccupants | None = None,
    ) -> ControlCommand:
        """The command for the coming step among `others` (every road user but this one)."""
        pose = status.pose
        s = self._locate(pose.x, pose.y, pose.yaw)
        front = s + model.cg_to_front_axle + model.front_overhang
        preview = STOP_PREVIEW_S * status.speed
        stop = min(
            self._stop_line_distance(front, status.speed, lights), self._dead_end_distance(front)
        )
        target = min(self._cruise_speed(s), self._braking_speed(stop - STOP_MARGIN_M - preview))
        if others is not None:
            gap, leader_speed = self._leader(s, front, others)
            room = gap - self.idm.min_gap_m - preview
            target = min(target, self._braking_speed(room, leader_speed))
        return ControlCommand(
            mode=LongitudinalMode.VELOCITY,
            velocity=max(target, 0.0),
            front_steer=self._pure_pursuit(model, status, s),
        )

    # -- where the vehicle is ------------------------------------------------------------

    def _locate(self, x: float, y: float, yaw: float) -> float:
        """The station on path[0], re-planning when the vehicle left its planned lanes."""
        lane_map = self.graph.lane_map
        for k, index in enumerate(self.path[:2]):
            lane = lane_map.lanes[lane_map.lane_ids[index]]
            s, off = _station_on(lane, x, y)
            if s < lane.length and off <= float(np.max(lane.widths)) / 2.0 + ON_LANE_MARGIN_M:
                if k > 0:
                    del self.path[:k]
                    self._yellow = _YELLOW_UNDECIDED
                self._extend_plan()
                return s
        projection = lane_map.project(x, y, yaw)
        self.path = [lane_map.lane_index(projection.lane_id)]
        self._yellow = _YELLOW_UNDECIDED
        self._extend_plan()
        return projection.s

    def _extend_plan(self) -> None:
        graph = self.graph
        while len(self.path) < PLANNED_LANES:
            successors = graph.successors[self.path[-1]]
            if not successors:
                return
            straight = [n for n in successors if graph.turn[n] == TURN_STRAIGHT]
            self.path.append((straight or list(successors))[0])

    # -- how fast ------------------------------------------------------------------------

    def _cruise_speed(self, s: float) -> float:
        graph, lane = self.graph, self.path[0]
        speed = float(graph.curve_speed[lane])
        if len(self.path) > 1:
            to_next = max(float(graph.length[lane]) - s, 0.0)
            next_curve = float(graph.curve_speed[self.path[1]])
            decel = self.idm.comfortable_decel_mps2
            speed = min(speed, math.sqrt(next_curve**2 + 2.0 * decel * to_next))
        return speed

    def _stop_line_distance(self, front: float, speed: float, lights: LightsView) -> float:
        """Front bumper to the next stop line whose light says stop (m), else inf."""
        graph, path = self.graph, self.path
        lane = path[0]
        if not np.isnan(graph.stop_s[lane]) and front <= graph.stop_s[lane]:
            line_lane, distance, movement = lane, graph.stop_s[lane] - front, 1
        elif len(path) > 1 and not np.isnan(graph.stop_s[path[1]]):
            line_lane = path[1]
            distance = graph.length[lane] - front + graph.stop_s[line_lane]
            movement = 2
        else:
            return math.inf
        light = int(graph.light[line_lane])
        if light < 0 or len(lights.aspects) == 0:
            return math.inf
        turn = int(graph.turn[path[movement]]) if movement < len(path) else TURN_STRAIGHT
        proceed, yellow = signal_permissions(
            lights, np.array([light], np.int64), np.array([turn], np.int64)
        )
        if proceed[0]:
            self._yellow = _YELLOW_UNDECIDED
            return math.inf
        if yellow[0] and self._yellow == _YELLOW_UNDECIDED:
            stoppable = self.idm.can_stop_within(np.array([speed]), np.array([distance]))[0]
            self._yellow = _YELLOW_STOP if stoppable else _YELLOW_PASS
        return math.inf if self._yellow == _YELLOW_PASS else float(distance)

    def _braking_speed(self, room: float, final_speed: float = 0.0) -> float:
        """The speed (m/s) from which comfortable braking reaches `final_speed` (m/s)
        within `room` (m)."""
        if math.isinf(room):
            return math.inf
        return math.sqrt(final_speed**2 + 2.0 * self.idm.comfortable_decel_mps2 * max(room, 0.0))

    def _leader(self, s: float, front: float, others: LaneOccupants) -> tuple[float, float]:
        """Gap from the front bumper to the nearest road user ahead on the planned lanes
        (m, inf if none) and that road user's speed along its lane (m/s)."""
        offset = 0.0
        for lane in self.path:
            on = others.lane == lane
            centre = offset + others.s[on]
            ahead = centre > s
            if np.any(ahead):
                nearest = int(np.argmin(np.where(ahead, centre, np.inf)))
                rear = centre[nearest] - others.half_length[on][nearest]
                return max(rear - front, 0.0), max(float(others.speed[on][nearest]), 0.0)
            offset += float(self.graph.length[lane])
        return math.inf, 0.0

    def _dead_end_distance(self, front: float) -> float:
        graph, path = self.graph, self.path
        if graph.successors[path[-1]]:
            return math.inf
        return float(sum(graph.length[n] for n in path)) - front

    # -- where to steer ------------------------------------------------------------------

    def _pure_pursuit(self, model: VehicleModel, status: VehicleStatus, s: float) -> float:
        """Front wheel angle (rad) that puts the rear axle on an arc through the point
        one look-ahead distance further along the planned lanes."""
        pose = status.pose
        lane_map = self.graph.lane_map
        lookahead = max(LOOKAHEAD_MIN_M, LOOKAHEAD_TIME_S * status.speed)
        route = [lane_map.lane_ids[n] for n in self.path[1:]]
        path = lane_map.lookahead(lane_map.lane_ids[self.path[0]], s, lookahead, route)
        target_x, target_y = path[-1]
        # The pose is the rear axle's midpoint.
        dx, dy = target_x - pose.x, target_y - pose.y
        alpha = math.atan2(dy, dx) - pose.yaw
        steer = math.atan2(2.0 * model.wheelbase * math.sin(alpha), math.hypot(dx, dy))
        return min(max(steer, -model.max_steer_front), model.max_steer_front)


def _station_on(lane: Lane, x: float, y: float) -> tuple[float, float]:
    """(station, distance) of the centreline point of `lane` nearest (x, y), m."""
    points = lane.centerline[:, :2]
    start, segment = points[:-1], np.diff(points, axis=0)
    squared = np.maximum(np.einsum("ij,ij->i", segment, segment), 1e-12)
    t = np.clip(np.einsum("ij,ij->i", np.array([x, y]) - start, segment) / squared, 0.0, 1.0)
    nearest = start + t[:, None] * segment
    distance = np.hypot(nearest[:, 0] - x, nearest[:, 1] - y)
    k = int(np.argmin(distance))
    return float(lane.stations[k] + t[k] * math.sqrt(squared[k])), float(distance[k])
