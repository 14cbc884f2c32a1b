"""NPC vehicles: vectorised kinematic lane followers driven by the IDM.

Each NPC is a row of parallel arrays (struct of arrays). Longitudinally it follows the
IDM towards its desired speed behind the nearest of: a road user ahead on its planned
path (two lanes of look-ahead), a stop line whose light tells it to stop, or the end of
a dead-end lane. Laterally it sits on its lane's centreline plus a fixed offset; at the
lane end it moves on to the successor it planned (its route, else a seeded random pick).
A scripted lane change puts it on the lane beside at once, at the offset it had, and
slides it to that lane's centreline along a half-cosine (no sideways speed at either
end), its heading turned with the sideways motion. An NPC given an activation distance
stands dormant, like a parked car, until an ego comes that close (`wake`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from egosim.world import kernels
from egosim.world.arrays import BoolArray, FloatArray, Indices, IntArray
from egosim.world.kernels import npc_motion
from egosim.world.traffic.activation import still_dormant
from egosim.world.traffic.idm import IntelligentDriverModel
from egosim.world.traffic.junction_rules import (
    DECISION_MARGIN_M,
    junction_conflicts,
    junction_entry_gap,
)
from egosim.world.traffic.lane_graph import LaneGraph
from egosim.world.traffic.leaders import LaneOccupants, leaders_ahead
from egosim.world.traffic.objects import ObjectTable, ObjectType
from egosim.world.traffic.signal_rules import LightsView, signal_permissions
from egosim.world.vehicle import VehicleModel

CRASH_BRAKE_DECEL_MPS2 = 7.0
"""A crashed NPC's driver brakes this hard (dry asphalt, full brake) until it stands."""
LOOKAHEAD_LANES = 2
"""Lanes beyond the current one searched for a leader and a stop line."""

# Every per-NPC field, for removing NPCs.
_PER_NPC_ARRAYS = (
    "unique_ids", "dims", "lane", "next_lanes", "s", "speed", "accel", "lateral",
    "target_speed", "speed_factor", "delay", "crashed", "yellow", "pose", "yaw_rate", "mass",
    "change_to", "change_timer", "change_duration", "slide_from", "slide_elapsed",
    "active_distance", "dormant", "wake_speed",
)  # fmt: skip
_PER_NPC_LISTS = ("names", "routes", "route_pos")

_MARGINS = np.array((DECISION_MARGIN_M, CRASH_BRAKE_DECEL_MPS2))
"""The junction decision margin and the crash deceleration, for the compiled step."""

# Latched reaction to a yellow, reset on every new lane and on every go aspect.
_YELLOW_UNDECIDED, _YELLOW_STOP, _YELLOW_PASS = 0, 1, 2


@dataclass(frozen=True)
class LaneChange:
    """Move into lane index `lane`, beside the NPC's, `after_s` s from now or as soon after
    as the NPC drives beside it, sliding across in `duration_s` s."""

    lane: int
    after_s: float = 0.0
    duration_s: float = 3.0


@dataclass(frozen=True)
class NpcSpawn:
    """One NPC to place: on lane index `lane` at station s (m), `lateral` m left of the
    centreline, moving at `speed` m/s. It drives at `target_speed` m/s when given, else at
    `speed_factor` times each lane's limit; it waits `start_delay_s` s before moving and
    follows `route` (lane indices) where the route names a successor, or the lane after a
    successor (routes may leave junction connectors out). With a finite
    `active_distance` (m) it stands until an ego comes within that distance of it, then
    sets off at `speed` (after its delay)."""

    unique_id: int
    model: VehicleModel
    lane: int
    s: float
    lateral: float = 0.0
    speed: float = 0.0
    target_speed: float | None = None
    speed_factor: float = 1.0
    route: tuple[int, ...] = field(default=())
    start_delay_s: float = 0.0
    lane_change: LaneChange | None = None
    active_distance: float = math.inf


class NpcFleet:
    """All NPC vehicles of a world."""

    def __init__(
        self,
        graph: LaneGraph,
        rng: np.random.Generator,
        idm: IntelligentDriverModel | None = None,
    ) -> None:
        self.graph = graph
        self.rng = rng
        self.idm = idm or IntelligentDriverModel()
        self.conflicts = junction_conflicts(graph.lane_map)
        # The lane graph's per-lane facts as the compiled step takes them.
        self._lane_facts = np.stack(
            (graph.length, graph.speed_limit, graph.curve_speed, graph.stop_s)
        ).astype(np.float64)
        self._lane_signals = np.stack((graph.light, graph.turn)).astype(np.int64)
        self._idm_table: tuple[IntelligentDriverModel | None, FloatArray] = (None, np.empty(0))
        self.clear()

    def clear(self) -> None:
        self.unique_ids = np.empty(0, np.int64)
        self.names: list[str] = []
        self.dims = np.empty((0, 3))
        self.mass = np.empty(0)
        """kg, of each NPC's catalogue model."""
        """length, width, height, m."""
        self.lane = np.empty(0, np.int64)
        self.next_lanes = np.empty((0, LOOKAHEAD_LANES), np.int64)
        self.s = np.empty(0)
        self.speed = np.empty(0)
        self.accel = np.empty(0)
        self.lateral = np.empty(0)
        self.target_speed = np.empty(0)
        """m/s; NaN: speed_factor times the lane's limit."""
        self.speed_factor = np.empty(0)
        self.delay = np.empty(0)
        self.crashed = np.empty(0, bool)
        self.yellow = np.empty(0, np.int8)
        self.routes: list[tuple[int, ...]] = []
        self.route_pos: list[int] = []
        self.pose = np.empty((0, 4))
        """x, y, z, heading of each NPC's centre."""
        self.yaw_rate = np.empty(0)
        self.change_to = np.empty(0, np.int64)
        """Lane index of a pending lane change, -1: none."""
        self.change_timer = np.empty(0)
        self.change_duration = np.empty(0)
        self.slide_from = np.empty(0)
        """Offset from the new lane's centreline when a lane change began, m."""
        self.slide_elapsed = np.empty(0)
        """Seconds since that lane change began; inf: not changing lanes."""
        self.active_distance = np.empty(0)
        """m; an ego this close wakes a dormant NPC."""
        self.dormant = np.empty(0, bool)
        """Per NPC: still waiting for an ego to come within its active distance."""
        self.wake_speed = np.empty(0)
        """m/s a dormant NPC sets off at (its spawn speed)."""
        self._pose_hints = np.empty(0, np.int64)
        """Where each NPC's pose search along the centrelines ended (see
        LaneMap.poses_at): it drives on a little a step, the next search starts there."""

    def __len__(self) -> int:
        return len(self.unique_ids)

    def spawn(self, spawns: Sequence[NpcSpawn]) -> None:
        if not spawns:
            return
        first = len(self)
        self.unique_ids = np.append(self.unique_ids, [n.unique_id for n in spawns])
        self.names += [n.model.name for n in spawns]
        self.dims = np.vstack(
            (self.dims, [(n.model.length, n.model.width, n.model.height) for n in spawns])
        )
        self.lane = np.append(self.lane, [n.lane for n in spawns]).astype(np.int64)
        self.s = np.append(self.s, [n.s for n in spawns])
        self.speed = np.append(self.speed, [n.speed for n in spawns])
        self.mass = np.append(self.mass, [n.model.mass for n in spawns])
        self.accel = np.append(self.accel, np.zeros(len(spawns)))
        self.lateral = np.append(self.lateral, [n.lateral for n in spawns])
        self.target_speed = np.append(
            self.target_speed,
            [math.nan if n.target_speed is None else n.target_speed for n in spawns],
        )
        self.speed_factor = np.append(self.speed_factor, [n.speed_factor for n in spawns])
        self.delay = np.append(self.delay, [n.start_delay_s for n in spawns])
        self.crashed = np.append(self.crashed, np.zeros(len(spawns), bool))
        self.yellow = np.append(self.yellow, np.zeros(len(spawns), np.int8))
        self.yaw_rate = np.append(self.yaw_rate, np.zeros(len(spawns)))
        changes = [n.lane_change or LaneChange(-1) for n in spawns]
        self.change_to = np.append(self.change_to, [c.lane for c in changes]).astype(np.int64)
        self.change_timer = np.append(self.change_timer, [c.after_s for c in changes])
        self.change_duration = np.append(self.change_duration, [c.duration_s for c in changes])
        self.slide_from = np.append(self.slide_from, np.zeros(len(spawns)))
        self.slide_elapsed = np.append(self.slide_elapsed, np.full(len(spawns), np.inf))
        distances = [n.active_distance for n in spawns]
        self.active_distance = np.append(self.active_distance, distances)
        self.dormant = np.append(self.dormant, np.isfinite(distances))
        self.wake_speed = np.append(self.wake_speed, [n.speed for n in spawns])
        self.speed[self.dormant] = 0.0
        self.next_lanes = np.vstack(
            (self.next_lanes, np.full((len(spawns), LOOKAHEAD_LANES), -1, np.int64))
        )
        for i, n in enumerate(spawns, start=first):
            starts_route = bool(n.route) and n.route[0] == n.lane
            self.routes.append(n.route)
            self.route_pos.append(1 if starts_route else 0)
            previous = int(self.lane[i])
            for k in range(LOOKAHEAD_LANES):
                previous = self._choose_successor(i, previous)
                self.next_lanes[i, k] = previous
        self.pose = self._poses()

    def remove(self, indices: Indices) -> None:
        """Take these NPCs out of the fleet (e.g. an NPC ghost takes one over)."""
        keep = np.ones(len(self), bool)
        keep[indices] = False
        for name in _PER_NPC_ARRAYS:
            setattr(self, name, getattr(self, name)[keep])
        for name in _PER_NPC_LISTS:
            setattr(self, name, [v for v, k in zip(getattr(self, name), keep, strict=True) if k])

    def _choose_successor(self, i: int, lane: int) -> int:
        """The lane NPC i takes after `lane`: its route's next match, else a random pick."""
        if lane < 0:
            return -1
        successors = self.graph.successors[lane]
        if not successors:
            return -1
        route = self.routes[i]
        for k in range(self.route_pos[i], len(route)):
            if route[k] in successors:
                self.route_pos[i] = k + 1
                return route[k]
            # Routes may skip junction connectors: take the one leading to the route's lane.
            for successor in successors:
                if route[k] in self.graph.successors[successor]:
                    self.route_pos[i] = k
                    return successor
        return successors[int(self.rng.integers(len(successors)))]

    def occupants(self) -> LaneOccupants:
        return LaneOccupants(self.lane, self.s, self.dims[:, 0] / 2.0, self.speed)

    def stop(self, indices: Indices) -> None:
        """Crash stop: these NPCs brake to a standstill (CRASH_BRAKE_DECEL_MPS2) and stay."""
        self.crashed[indices] = True

    def parked(self) -> BoolArray:
        """Per NPC: still waiting to set off (a parked car, immovable in a contact)."""
        parked: BoolArray = (self.delay > 0.0) | self.dormant
        return parked

    def wake(self, points: FloatArray) -> None:
        """Dormant NPCs within their active distance of any of `points` (K, 2) m (the
        egos) wake up, for good, moving at their spawn speed."""
        dormant = still_dormant(self.dormant, self.pose, self.active_distance, points)
        woken = self.dormant & ~dormant
        self.speed[woken] = self.wake_speed[woken]
        self.dormant = dormant

    def shove(self, indices: IntArray, displacement: FloatArray, velocity: FloatArray) -> None:
        """A contact's response: move NPCs `indices` by `displacement` (K, 2) m and take
        the part of `velocity` (K, 2) m/s along their lane (an NPC does not reverse)."""
        heading = self.pose[indices, 3]
        along = np.column_stack((np.cos(heading), np.sin(heading)))
        left = np.column_stack((-np.sin(heading), np.cos(heading)))
        lengths = self.graph.length[self.lane[indices]]
        self.s[indices] = np.clip(
            self.s[indices] + np.einsum("kd,kd->k", displacement, along), 0.0, lengths
        )
        self.lateral[indices] += np.einsum("kd,kd->k", displacement, left)
        self.speed[indices] = np.maximum(np.einsum("kd,kd->k", velocity, along), 0.0)
        self.pose = self._poses()

    def step(self, dt: float, lights: LightsView, others: LaneOccupants) -> None:
        """Advance dt s among `others` (ego, pedestrians, obstacles placed on lanes)."""
        n = len(self)
        if n == 0:
            return
        if kernels.ACTIVE and self.idm.integer_delta():
            self._step_compiled(dt, lights, others)
            return
        graph = self.graph
        waiting = (self.delay > 0.0) | self.dormant
        self.delay = np.where(self.dormant, self.delay, np.maximum(self.delay - dt, 0.0))
        frozen = waiting | self.crashed

        occupants = LaneOccupants.concatenate([self.occupants(), others])
        slots = np.arange(n)
        distance, leader = leaders_ahead(graph, occupants, slots, self.next_lanes)
        half = self.dims[:, 0] / 2.0
        has_leader = leader >= 0
        safe_leader = np.where(has_leader, leader, 0)
        gap = np.where(has_leader, distance - half - occupants.half_length[safe_leader], np.inf)
        closing = np.where(has_leader, self.speed - occupants.speed[safe_leader], 0.0)

        v0 = self._desired_speed()
        accel = self.idm.acceleration(self.speed, v0, gap, closing)
        stop_gap = np.minimum(
            np.minimum(self._stop_line_gap(lights, half), self._dead_end_gap(half)),
            self._junction_gap(occupants, half),
        )
        accel = np.minimum(accel, self.idm.acceleration(self.speed, v0, stop_gap, self.speed))
        accel[waiting] = 0.0
        accel[self.crashed] = -np.minimum(self.speed[self.crashed] / dt, CRASH_BRAKE_DECEL_MPS2)

        new_speed = np.maximum(self.speed + accel * dt, 0.0)
        new_speed[waiting] = 0.0
        self.s = self.s + 0.5 * (self.speed + new_speed) * dt
        self.accel = (new_speed - self.speed) / dt
        self.speed = new_speed
        self._advance_lanes(np.flatnonzero(self.s > self.graph.length[self.lane]))
        self._change_lanes(dt, frozen)
        self._turn(dt)

    def _step_compiled(self, dt: float, lights: LightsView, others: LaneOccupants) -> None:
        """step() through kernels/npc_motion.py: the same arithmetic, the same results."""
        moved, past_end, due = npc_motion.advance(
            dt,
            self.lane,
            self.next_lanes,
            self.s,
            self.speed,
            self.dims,
            self.target_speed,
            self.speed_factor,
            self.delay,
            self.dormant,
            self.crashed,
            self.yellow,
            others.lane,
            others.s,
            others.half_length,
            others.speed,
            self._lane_facts,
            self._lane_signals,
            self.graph.is_junction,
            self.conflicts,
            lights.aspects,
            lights.flashing,
            lights.arrow_head,
            lights.arrow_only,
            self._idm_figures(),
            int(self.idm.delta),
            _MARGINS,
            self.slide_elapsed,
            self.change_duration,
            self.slide_from,
            self.lateral,
            self.change_to,
            self.change_timer,
        )
        self.s, self.speed, self.accel, self.delay = moved
        if len(past_end):
            self._advance_lanes(past_end)
        if len(due):
            self._change_lanes_now(due)
        self._turn(dt)

    def _turn(self, dt: float) -> None:
        """The poses on the lanes now, and the yaw rate (rad/s) that took them there."""
        earlier = self.pose
        self.pose = self._poses()
        if kernels.ACTIVE:
            self.yaw_rate = npc_motion.yaw_rates(self.pose, earlier, dt)
            return
        self.yaw_rate = np.remainder(self.pose[:, 3] - earlier[:, 3] + math.pi, math.tau) - math.pi
        self.yaw_rate /= dt

    def _idm_figures(self) -> FloatArray:
        """The IDM's figures as kernels/npc_motion.py takes them (kept while the IDM is)."""
        idm = self.idm
        if self._idm_table[0] is not idm:
            figures = (
                idm.time_headway_s,
                idm.min_gap_m,
                idm.max_accel_mps2,
                idm.comfortable_decel_mps2,
                idm.max_decel_mps2,
            )
            self._idm_table = (idm, np.array(figures))
        return self._idm_table[1]

    def _desired_speed(self) -> FloatArray:
        """IDM v0: scripted or lane-limit speed, capped by this lane's and (braking at the
        comfortable rate) the next lane's curve speed."""
        graph = self.graph
        base = np.where(
            np.isnan(self.target_speed),
            graph.speed_limit[self.lane] * self.speed_factor,
            self.target_speed,
        )
        nxt = self.next_lanes[:, 0]
        to_next = graph.length[self.lane] - self.s
        next_curve = np.where(nxt >= 0, graph.curve_speed[np.maximum(nxt, 0)], np.inf)
        approach = np.sqrt(
            next_curve**2 + 2.0 * self.idm.comfortable_decel_mps2 * np.maximum(to_next, 0.0)
        )
        speed: FloatArray = np.maximum(
            np.minimum.reduce([base, graph.curve_speed[self.lane], approach]), 0.1
        )
        return speed

    def _stop_line_gap(self, lights: LightsView, half: FloatArray) -> FloatArray:
        """Bumper-to-stop-line distance (m) where a light says stop, else inf."""
        graph = self.graph
        if len(lights.aspects) == 0:
            return np.full(len(self), np.inf)
        lane, nxt = self.lane, self.next_lanes[:, 0]
        front = self.s + half
        here = ~np.isnan(graph.stop_s[lane]) & (front <= graph.stop_s[lane])
        safe_next = np.maximum(nxt, 0)
        ahead = ~here & (nxt >= 0) & ~np.isnan(graph.stop_s[safe_next])
        line_lane = np.where(here, lane, safe_next)
        distance = np.where(
            here, graph.stop_s[lane] - front, graph.length[lane] - front + graph.stop_s[safe_next]
        )
        relevant = (here | ahead) & (graph.light[line_lane] >= 0)
        movement = np.where(here, nxt, self.next_lanes[:, 1])
        turn = np.where(movement >= 0, graph.turn[np.maximum(movement, 0)], 0)
        light = np.where(relevant, graph.light[line_lane], 0)
        proceed, yellow = signal_permissions(lights, light, turn)

        self.yellow[proceed] = _YELLOW_UNDECIDED
        undecided = relevant & yellow & (self.yellow == _YELLOW_UNDECIDED)
        stoppable = self.idm.can_stop_within(self.speed, distance)
        self.yellow[undecided] = np.where(stoppable[undecided], _YELLOW_STOP, _YELLOW_PASS)
        must_stop = relevant & ~proceed & (self.yellow != _YELLOW_PASS)
        return np.where(must_stop, distance, np.inf)

    def _junction_gap(self, occupants: LaneOccupants, half: FloatArray) -> FloatArray:
        """Distance (m) to the junction entry where yielding or a full exit holds it."""
        graph = self.graph
        lanes = len(graph)
        occupied = np.zeros(lanes, dtype=bool)
        occupied[occupants.lane] = True
        rear = np.full(lanes + 1, np.inf)
        np.minimum.at(rear, occupants.lane, occupants.s - occupants.half_length)
        entering = np.where(graph.is_junction[self.lane], -1, self.next_lanes[:, 0])
        entry_distance = graph.length[self.lane] - self.s - half
        decision = self.speed**2 / (2.0 * self.idm.comfortable_decel_mps2) + DECISION_MARGIN_M
        return junction_entry_gap(
            self.conflicts,
            graph.is_junction,
            entry_distance,
            entering,
            exit_room=rear[self.next_lanes[:, 1]],
            needed_room=self.dims[:, 0] + self.idm.min_gap_m,
            stoppable=self.idm.can_stop_within(self.speed, entry_distance),
            occupied=occupied,
            decision_distance=decision,
        )

    def _dead_end_gap(self, half: FloatArray) -> FloatArray:
        dead_end = self.next_lanes[:, 0] < 0
        return np.where(dead_end, self.graph.length[self.lane] - self.s - half, np.inf)

    def _advance_lanes(self, past_end: IntArray) -> None:
        """NPCs `past_end` (beyond their lane's end) onto the lanes they planned."""
        length = self.graph.length
        for i in past_end:
            while self.s[i] > length[self.lane[i]]:
                nxt = int(self.next_lanes[i, 0])
                if nxt < 0:
                    self.s[i] = length[self.lane[i]]
                    self.speed[i] = 0.0
                    break
                self.s[i] -= length[self.lane[i]]
                self.lane[i] = nxt
                self.next_lanes[i, :-1] = self.next_lanes[i, 1:]
                self.next_lanes[i, -1] = self._choose_successor(int(i), int(self.next_lanes[i, -2]))
                self.yellow[i] = _YELLOW_UNDECIDED

    def _change_lanes(self, dt: float, frozen: BoolArray) -> None:
        """Scripted lane changes that are due, and the sideways slides they started."""
        sliding = np.isfinite(self.slide_elapsed)
        self.slide_elapsed[sliding] += dt
        progress = np.clip(self.slide_elapsed / self.change_duration, 0.0, 1.0)
        self.lateral[sliding] = (self.slide_from * 0.5 * (1.0 + np.cos(math.pi * progress)))[
            sliding
        ]
        self.slide_elapsed[sliding & (progress >= 1.0)] = np.inf
        pending = self.change_to >= 0
        self.change_timer[pending] -= dt
        self._change_lanes_now(np.flatnonzero(pending & (self.change_timer <= 0.0) & ~frozen))

    def _change_lanes_now(self, due: IntArray) -> None:
        """The lane changes of NPCs `due` whose target lies beside them."""
        lanes = self.graph.lane_map.lanes
        ids = self.graph.lane_map.lane_ids
        for i in due:
            here, target = lanes[ids[self.lane[i]]], ids[self.change_to[i]]
            if target in (here.left_neighbor, here.right_neighbor):
                self._move_beside(int(i), int(self.change_to[i]))

    def _move_beside(self, i: int, target: int) -> None:
        """NPC i onto lane `target` at the same place, then sliding to its centreline."""
        length = self.graph.length
        lane_map = self.graph.lane_map
        x, y, _, _ = self.pose[i]
        s = min(self.s[i] * length[target] / length[self.lane[i]], length[target])
        cx, cy, _, heading = lane_map.poses_at(np.array([target]), np.array([s]))[0]
        self.lateral[i] = -(x - cx) * math.sin(heading) + (y - cy) * math.cos(heading)
        self.slide_from[i] = self.lateral[i]
        self.slide_elapsed[i] = 0.0
        self.lane[i], self.s[i] = target, s
        self.change_to[i] = -1
        self.yellow[i] = _YELLOW_UNDECIDED
        previous = target
        for k in range(LOOKAHEAD_LANES):
            previous = self._choose_successor(i, previous)
            self.next_lanes[i, k] = previous

    def _poses(self) -> FloatArray:
        if len(self._pose_hints) != len(self):
            self._pose_hints = np.zeros(len(self), np.int64)
        pose = self.graph.lane_map.poses_at(self.lane, self.s, self.lateral, self._pose_hints)
        sliding = np.isfinite(self.slide_elapsed)
        if np.any(sliding):
            # The heading follows the slide: d(lateral)/dt against the forward speed.
            duration = self.change_duration[sliding]
            progress = self.slide_elapsed[sliding] / duration
            sideways = -self.slide_from[sliding] * math.pi / (2.0 * duration)
            sideways *= np.sin(math.pi * progress)
            pose[sliding, 3] += np.arctan2(sideways, np.maximum(self.speed[sliding], 0.1))
        return pose

    def table(self) -> ObjectTable:
        heading = self.pose[:, 3]
        if kernels.ACTIVE:
            velocity, acceleration = npc_motion.planar_motion(
                heading, self.speed, self.accel, self.yaw_rate
            )
        else:
            direction = np.column_stack((np.cos(heading), np.sin(heading), np.zeros(len(self))))
            normal = np.column_stack((-np.sin(heading), np.cos(heading), np.zeros(len(self))))
            velocity = self.speed[:, None] * direction
            acceleration = (
                self.accel[:, None] * direction + (self.speed * self.yaw_rate)[:, None] * normal
            )
        return ObjectTable(
            unique_ids=self.unique_ids,
            object_types=np.full(len(self), int(ObjectType.NPC_VEHICLE), np.int64),
            names=tuple(self.names),
            positions=self.pose[:, :3].copy(),
            headings=heading.copy(),
            velocities=velocity,
            accelerations=acceleration,
            sizes=self.dims.copy(),
        )
