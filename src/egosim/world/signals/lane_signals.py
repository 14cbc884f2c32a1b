"""What a driver at a stop line obeys: every head governing it, read as one signal.

Several heads may govern one stop line: K-City hangs a red/yellow/green head beside a
red/yellow/left-arrow/green head over the same lanes. A driver reads them together, as the
lamps lit on any of them: the arrow lit on one head lets the left turn go while the round
red of the other holds the through traffic. Dark heads add nothing (the stop line is dark
only when all its heads are), and a flashing-yellow head beside heads that cycle adds
nothing either (the signal flashes only when all its heads do). The signal has a left
arrow when any head has one and a round green when any head has one.

GetTrafficLightStatus still names one head: the nearest one (signals.governing).
"""

from __future__ import annotations

from collections.abc import Iterable

import numpy as np

from egosim.world.arrays import BoolArray, IntArray
from egosim.world.map import LaneMap
from egosim.world.map.light_type import LightType
from egosim.world.signals.aspects import LEFT_ARROW_TYPES, OFF, has_green


def combined_aspect(aspects: Iterable[int]) -> int:
    """The lamps lit on any of a stop line's heads; OFF when every head is dark."""
    lit = 0
    for aspect in aspects:
        if aspect > 0:
            lit |= aspect
    return lit if lit else OFF


class LaneSignals:
    """Every signal a driver may face, numbered: signal k < len(light_ids) is head k on its
    own; each further signal is a set of heads governing some lane together.

    `of_lane[i]` is the signal of lane i (LaneMap.lane_ids order), -1 for a lane without a
    light. `flashing`, `arrow` and `arrow_only` say per signal whether it only flashes
    yellow, has a left arrow, and has a left arrow but no round green.
    """

    def __init__(self, lane_map: LaneMap, light_ids: tuple[str, ...]) -> None:
        index = {light_id: k for k, light_id in enumerate(light_ids)}
        sets: dict[tuple[int, ...], int] = {}
        self.of_lane: IntArray = np.full(len(lane_map.lane_ids), -1, dtype=np.int64)
        for k, lane_id in enumerate(lane_map.lane_ids):
            heads = tuple(index[i] for i in lane_map.lanes[lane_id].traffic_light_ids)
            if len(heads) == 1:
                self.of_lane[k] = heads[0]
            elif heads:
                self.of_lane[k] = sets.setdefault(heads, len(light_ids) + len(sets))
        width = max((len(heads) for heads in sets), default=0)
        self._members: IntArray = np.array(
            [list(heads) + [-1] * (width - len(heads)) for heads in sets], dtype=np.int64
        ).reshape(len(sets), width)
        self._present: BoolArray = self._members >= 0
        types = [int(lane_map.traffic_lights[i].light_type) for i in light_ids]
        flashing = np.array([t == LightType.FLASHING_YELLOW for t in types], dtype=bool)
        arrow = np.array([t in LEFT_ARROW_TYPES for t in types], dtype=bool)
        green = np.array([has_green(t) for t in types], dtype=bool)
        self._all_flashing = self._every(flashing)
        self.flashing: BoolArray = np.concatenate((flashing, self._all_flashing))
        self.arrow: BoolArray = np.concatenate((arrow, self._any(arrow)))
        self.arrow_only: BoolArray = np.concatenate(
            (arrow & ~green, self._any(arrow) & ~self._any(green))
        )

    def __len__(self) -> int:
        return len(self.flashing)

    def _member_values(self, per_head: BoolArray) -> BoolArray:
        values: BoolArray = per_head[np.maximum(self._members, 0)] & self._present
        return values

    def _any(self, per_head: BoolArray) -> BoolArray:
        return np.asarray(np.any(self._member_values(per_head), axis=1), dtype=bool)

    def _every(self, per_head: BoolArray) -> BoolArray:
        values = self._member_values(per_head) | ~self._present
        return np.asarray(np.all(values, axis=1), dtype=bool)

    def aspects(self, head_aspects: IntArray) -> IntArray:
        """Every signal's aspect from the heads' aspects (light_ids order)."""
        if not len(self._members):
            return head_aspects
        aspect = head_aspects[np.maximum(self._members, 0)]
        flashing = self.flashing[np.maximum(self._members, 0)]
        counted = self._present & (aspect > 0) & (~flashing | self._all_flashing[:, None])
        lit = np.bitwise_or.reduce(np.where(counted, aspect, 0), axis=1)
        combined: IntArray = np.concatenate((head_aspects, np.where(lit > 0, lit, OFF)))
        return combined
