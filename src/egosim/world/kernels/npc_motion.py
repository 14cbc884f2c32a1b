"""The NPC fleet's step (traffic/npc_vehicles.py) as compiled loops: leader search, IDM,
stop lines, dead ends, junction yielding, integration, lane-change slides and motion.

Each function mirrors the numpy code it replaces operation for operation; the comments
name that code. The IDM's (v / v0)^delta is a repeated product for the integer delta the
caller checks for (traffic/idm.py computes it the same way).
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

from egosim.world.arrays import BoolArray, FloatArray, IntArray
from egosim.world.kernels import kernel
from egosim.world.kernels.numpy_scalars import clip, maximum, minimum, remainder
from egosim.world.kernels.sorting import lexsort_argsort, search_sorted

_UNDECIDED, _STOP, _PASS = 0, 1, 2  # npc_vehicles' yellow latch
_YELLOW, _GREEN, _GREEN_LEFT = 4, 16, 32  # signals.aspects
_TURN_LEFT = 1  # lane_graph.TURN_LEFT


@kernel
def integer_power(x: float, exponent: int) -> float:
    """x ** exponent as traffic/idm.py's integer_power computes it: x * x * ... left to
    right (exponent >= 0)."""
    result = 1.0
    for k in range(exponent):
        result = x if k == 0 else result * x
    return result


@kernel
def idm_acceleration(
    v: float, v0: float, gap: float, dv: float, idm: FloatArray, exponent: int
) -> float:
    """IntelligentDriverModel.acceleration for one vehicle; idm holds time headway, min
    gap, max accel, comfortable decel and max decel."""
    headway, min_gap, max_accel, comfortable, max_decel = idm[0], idm[1], idm[2], idm[3], idm[4]
    free = 1.0 - integer_power(v / v0, exponent)
    brake_term = v * dv / (2.0 * math.sqrt(max_accel * comfortable))
    desired = min_gap + maximum(0.0, v * headway + brake_term)
    ratio = desired / maximum(gap, 1e-3)
    accel = max_accel * (free - ratio * ratio)
    return clip(accel, -max_decel, max_accel)


@kernel
def _leaders(
    n: int,
    lane: IntArray,
    s: FloatArray,
    next_lanes: IntArray,
    length: FloatArray,
) -> tuple[FloatArray, IntArray]:
    """leaders.leaders_ahead for followers 0..n-1 of the occupants (lane, s)."""
    m = lane.shape[0]
    order = lexsort_argsort(lane, s)  # np.lexsort((s, lane))
    sorted_lane = lane[order]
    rank = np.empty(m, dtype=np.int64)
    for k in range(m):
        rank[order[k]] = k
    distance = np.full(n, np.inf)
    leader = np.full(n, -1, dtype=np.int64)
    for i in range(n):
        behind = rank[i] + 1
        if behind < m and sorted_lane[behind] == lane[i]:
            distance[i] = s[order[behind]] - s[i]
            leader[i] = order[behind]
        offset = length[lane[i]] - s[i]
        for k in range(next_lanes.shape[1]):
            target = next_lanes[i, k]
            if leader[i] < 0 and target >= 0:
                first = search_sorted(sorted_lane, target, False)
                if first < m and sorted_lane[first] == target:
                    candidate = order[first]
                    if candidate != i:
                        distance[i] = offset + s[candidate]
                        leader[i] = candidate
            offset = offset + (length[target] if target >= 0 else np.inf)
    return distance, leader


@kernel
def _junction_gaps(
    n: int,
    lane: IntArray,
    s: FloatArray,
    half_length: FloatArray,
    npc_s: FloatArray,
    speed: FloatArray,
    half: FloatArray,
    next_lanes: IntArray,
    needed_room: FloatArray,
    length: FloatArray,
    is_junction: BoolArray,
    conflicts: IntArray,
    comfortable: float,
    decision_margin: float,
) -> FloatArray:
    """NpcFleet._junction_gap with junction_rules.junction_entry_gap."""
    lanes = length.shape[0]
    occupied = np.zeros(lanes + 1, dtype=np.bool_)
    rear = np.full(lanes + 1, np.inf)
    for k in range(lane.shape[0]):
        occupied[lane[k]] = True
        rear[lane[k]] = minimum(rear[lane[k]], s[k] - half_length[k])
    gap = np.full(n, np.inf)
    rows = np.empty(n, dtype=np.int64)
    entry = np.empty(n)
    count = 0
    for i in range(n):
        entering = -1 if is_junction[lane[i]] else next_lanes[i, 0]
        entry_distance = length[lane[i]] - npc_s[i] - half[i]
        decision = speed[i] * speed[i] / (2.0 * comfortable) + decision_margin
        if entering >= 0 and entry_distance <= decision and is_junction[entering]:
            rows[count] = i
            entry[count] = entry_distance
            count += 1
    if count == 0:
        return gap
    claimed = np.zeros(lanes + 1, dtype=np.bool_)
    for k in lexsort_argsort(np.zeros(count, dtype=np.int64), entry[:count]):
        i = rows[k]
        entering = next_lanes[i, 0]
        exit_lane = next_lanes[i, 1]
        blocked = rear[exit_lane if exit_lane >= 0 else lanes] < needed_room[i]
        for c in conflicts[entering]:
            if c >= 0 and (occupied[c] or claimed[c]):
                blocked = True
        stoppable = speed[i] * speed[i] <= 2.0 * comfortable * entry[k]
        if blocked and stoppable:
            gap[i] = entry[k]
        else:
            claimed[entering] = True
    return gap


@kernel
def advance(
    dt: float,
    lane: IntArray,
    next_lanes: IntArray,
    s: FloatArray,
    speed: FloatArray,
    dims: FloatArray,
    target_speed: FloatArray,
    speed_factor: FloatArray,
    delay: FloatArray,
    dormant: BoolArray,
    crashed: BoolArray,
    yellow: npt.NDArray[np.int8],
    others_lane: IntArray,
    others_s: FloatArray,
    others_half: FloatArray,
    others_speed: FloatArray,
    graph: FloatArray,
    graph_lanes: IntArray,
    is_junction: BoolArray,
    conflicts: IntArray,
    aspects: IntArray,
    flashing: BoolArray,
    arrow_head: BoolArray,
    arrow_only: BoolArray,
    idm: FloatArray,
    exponent: int,
    margins: FloatArray,
    slide_elapsed: FloatArray,
    change_duration: FloatArray,
    slide_from: FloatArray,
    lateral: FloatArray,
    change_to: IntArray,
    change_timer: FloatArray,
) -> tuple[FloatArray, IntArray, IntArray]:
    """NpcFleet.step up to the lane bookkeeping: (4, N) new s, speed, accel and delay,
    who ran past their lane's end, and whose lane change is due; the lane-change slides
    and timers run on in place (see slide).

    The others are the other occupants of lanes. graph rows: length, speed limit, curve
    speed, stop station; graph_lanes rows: light, turn. idm: time headway, min gap, max
    accel, comfortable decel, max decel. margins: junction decision margin, crash
    decel. yellow (the latch) is updated in place.
    """
    n = lane.shape[0]
    length, speed_limit, curve_speed, stop_s = graph[0], graph[1], graph[2], graph[3]
    light_of, turn_of = graph_lanes[0], graph_lanes[1]
    comfortable = idm[3]
    m = n + others_lane.shape[0]
    occupant_lane = np.empty(m, dtype=np.int64)
    occupant_s = np.empty(m)
    occupant_half = np.empty(m)
    occupant_speed = np.empty(m)
    half = np.empty(n)
    for i in range(n):
        half[i] = dims[i, 0] / 2.0
        occupant_lane[i], occupant_s[i] = lane[i], s[i]
        occupant_half[i], occupant_speed[i] = half[i], speed[i]
    for k in range(others_lane.shape[0]):
        occupant_lane[n + k], occupant_s[n + k] = others_lane[k], others_s[k]
        occupant_half[n + k], occupant_speed[n + k] = others_half[k], others_speed[k]

    distance, leader = _leaders(n, occupant_lane, occupant_s, next_lanes, length)
    needed_room = np.empty(n)
    for i in range(n):
        needed_room[i] = dims[i, 0] + idm[1]
    junction_gap = _junction_gaps(
        n, occupant_lane, occupant_s, occupant_half, s, speed, half, next_lanes,
        needed_room, length, is_junction, conflicts, comfortable, margins[0],
    )  # fmt: skip

    result = np.empty((4, n))
    frozen = np.empty(n, dtype=np.bool_)
    past_end = np.empty(n, dtype=np.int64)
    passed = 0
    has_lights = aspects.shape[0] > 0
    for i in range(n):
        here_lane, nxt, after = lane[i], next_lanes[i, 0], next_lanes[i, 1]
        v = speed[i]
        waiting = delay[i] > 0.0 or dormant[i]
        frozen[i] = waiting or crashed[i]
        result[3, i] = delay[i] if dormant[i] else maximum(delay[i] - dt, 0.0)
        if leader[i] >= 0:
            gap = distance[i] - half[i] - occupant_half[leader[i]]
            closing = v - occupant_speed[leader[i]]
        else:
            gap, closing = np.inf, 0.0
        # _desired_speed
        if target_speed[i] != target_speed[i]:
            base = speed_limit[here_lane] * speed_factor[i]
        else:
            base = target_speed[i]
        next_curve = curve_speed[nxt] if nxt >= 0 else np.inf
        approach = math.sqrt(
            next_curve * next_curve + 2.0 * comfortable * maximum(length[here_lane] - s[i], 0.0)
        )
        v0 = maximum(minimum(minimum(base, curve_speed[here_lane]), approach), 0.1)
        accel = idm_acceleration(v, v0, gap, closing, idm, exponent)
        # _stop_line_gap
        line_gap = np.inf
        if has_lights:
            front = s[i] + half[i]
            here = stop_s[here_lane] == stop_s[here_lane] and front <= stop_s[here_lane]
            safe_next = max(nxt, 0)
            ahead = not here and nxt >= 0 and stop_s[safe_next] == stop_s[safe_next]
            line_lane = here_lane if here else safe_next
            if here:
                line_distance = stop_s[here_lane] - front
            else:
                line_distance = length[here_lane] - front + stop_s[safe_next]
            relevant = (here or ahead) and light_of[line_lane] >= 0
            movement = nxt if here else after
            turn = turn_of[movement] if movement >= 0 else 0
            light = light_of[line_lane] if relevant else 0
            # signal_rules.signal_permissions
            aspect = aspects[light]
            dark = aspect < 0 or flashing[light]
            on_arrow = (turn == _TURN_LEFT and arrow_head[light]) or arrow_only[light]
            go_lamp = _GREEN_LEFT if on_arrow else _GREEN
            lit = 0 if dark else aspect
            proceed = dark or (lit & go_lamp) != 0
            shows_yellow = not proceed and (lit & _YELLOW) != 0
            if proceed:
                yellow[i] = _UNDECIDED
            if relevant and shows_yellow and yellow[i] == _UNDECIDED:
                stoppable = v * v <= 2.0 * comfortable * line_distance
                yellow[i] = _STOP if stoppable else _PASS
            if relevant and not proceed and yellow[i] != _PASS:
                line_gap = line_distance
        dead_end_gap = length[here_lane] - s[i] - half[i] if nxt < 0 else np.inf
        stop_gap = minimum(minimum(line_gap, dead_end_gap), junction_gap[i])
        accel = minimum(accel, idm_acceleration(v, v0, stop_gap, v, idm, exponent))
        if waiting:
            accel = 0.0
        if crashed[i]:
            accel = -minimum(v / dt, margins[1])
        new_speed = maximum(v + accel * dt, 0.0)
        if waiting:
            new_speed = 0.0
        result[0, i] = s[i] + 0.5 * (v + new_speed) * dt
        result[2, i] = (new_speed - v) / dt
        result[1, i] = new_speed
        if result[0, i] > length[here_lane]:
            past_end[passed] = i
            passed += 1
    # The slides touch none of the state above, nor does the lane bookkeeping that the
    # caller does in between touch theirs: running them here changes no result.
    due = slide(
        dt, slide_elapsed, change_duration, slide_from, lateral, change_to, change_timer, frozen
    )
    return result, past_end[:passed], due


@kernel
def slide(
    dt: float,
    slide_elapsed: FloatArray,
    change_duration: FloatArray,
    slide_from: FloatArray,
    lateral: FloatArray,
    change_to: IntArray,
    change_timer: FloatArray,
    frozen: BoolArray,
) -> IntArray:
    """NpcFleet._change_lanes up to the moves themselves (in place): the slides that run
    and the timers of pending changes; returns the NPCs whose change is due."""
    n = lateral.shape[0]
    due = np.empty(n, dtype=np.int64)
    count = 0
    for i in range(n):
        if math.isfinite(slide_elapsed[i]):
            slide_elapsed[i] += dt
            progress = clip(slide_elapsed[i] / change_duration[i], 0.0, 1.0)
            lateral[i] = slide_from[i] * 0.5 * (1.0 + math.cos(math.pi * progress))
            if progress >= 1.0:
                slide_elapsed[i] = np.inf
        if change_to[i] >= 0:
            change_timer[i] -= dt
            if change_timer[i] <= 0.0 and not frozen[i]:
                due[count] = i
                count += 1
    return due[:count]


@kernel
def yaw_rates(pose: FloatArray, earlier_pose: FloatArray, dt: float) -> FloatArray:
    """NpcFleet._turn's yaw rates: the heading turned from earlier_pose to pose (both
    (N, 4) x, y, z, heading), wrapped to [-pi, pi), over dt."""
    n = pose.shape[0]
    rate = np.empty(n)
    for i in range(n):
        rate[i] = remainder(pose[i, 3] - earlier_pose[i, 3] + math.pi, math.tau) - math.pi
        rate[i] /= dt
    return rate


@kernel
def planar_motion(
    heading: FloatArray, speed: FloatArray, accel: FloatArray, yaw_rate: FloatArray
) -> tuple[FloatArray, FloatArray]:
    """NpcFleet.table's (N, 3) velocities and accelerations in the map frame."""
    n = heading.shape[0]
    velocity = np.empty((n, 3))
    acceleration = np.empty((n, 3))
    for i in range(n):
        c, s = math.cos(heading[i]), math.sin(heading[i])
        turning = speed[i] * yaw_rate[i]
        velocity[i, 0] = speed[i] * c
        velocity[i, 1] = speed[i] * s
        velocity[i, 2] = speed[i] * 0.0
        acceleration[i, 0] = accel[i] * c + turning * -s
        acceleration[i, 1] = accel[i] * s + turning * c
        acceleration[i, 2] = accel[i] * 0.0 + turning * 0.0
    return velocity, acceleration
