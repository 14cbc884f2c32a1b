"""Recorded topics as numpy columns, sampled at any time between their messages.

Each track holds one row per message (times in s from the bag's start,
ascending) and answers `sample(t)` with a bisection and one row of arithmetic,
so sampling costs the same for a minute or an hour of recording. A track is made from
its topic's messages in whichever release the bag was recorded (releases.py).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, overload

import numpy as np

from egosim.world.arrays import FloatArray

from .frame import ControlCommand, EgoState, ObjectState, Vector

if TYPE_CHECKING:
    from egosim.msgs.typed import morai_24_r2, morai_26_r1, morai_2021_08, standard

    EgoStatus = (
        morai_26_r1.EgoVehicleStatus | morai_24_r2.EgoVehicleStatus | morai_2021_08.EgoVehicleStatus
    )
    """An EgoVehicleStatus of any release (before 26.r1: the front steer is `wheel_angle`,
    and there is no rear steer)."""
    ObjectList = (
        morai_26_r1.ObjectStatusList | morai_24_r2.ObjectStatusList | morai_2021_08.ObjectStatusList
    )
    CtrlCmd = morai_26_r1.CtrlCmd | morai_24_r2.CtrlCmd | morai_2021_08.CtrlCmd
    """A CtrlCmd of any release (before 26.r1: the front steer is `steering`, and there is
    no rear steer)."""

KMH_TO_MS = 1.0 / 3.6
TWO_PI = 2.0 * math.pi


def _bracket(times: np.ndarray, t: float) -> tuple[int, int, float]:
    """Rows (i, j) around `t` and the fraction of the way from i to j (held at both ends)."""
    last = len(times) - 1
    i = int(np.searchsorted(times, t, side="right")) - 1
    if i < 0:
        return 0, 0, 0.0
    if i >= last:
        return last, last, 0.0
    span = times[i + 1] - times[i]
    return i, i + 1, float((t - times[i]) / span) if span > 0 else 0.0


@overload
def _wrap(angle: float) -> float: ...
@overload
def _wrap(angle: FloatArray) -> FloatArray: ...
def _wrap(angle: float | FloatArray) -> float | FloatArray:
    """Angles (rad) into [-pi, pi)."""
    return (angle + math.pi) % TWO_PI - math.pi


def _vector(vector: standard.Vector3) -> list[float]:
    return [vector.x, vector.y, vector.z]


def _ego_steer(m: EgoStatus) -> list[float]:
    """Front and rear steer, deg."""
    if hasattr(m, "wheel_angle"):  # a release before 26.r1
        return [m.wheel_angle, 0.0]
    return [m.front_steer_angle, m.rear_steer_angle]


def _command_steer(m: CtrlCmd) -> list[float]:
    """Front and rear steer, rad."""
    if hasattr(m, "steering"):  # a release before 26.r1
        return [m.steering, 0.0]
    return [m.front_steer, m.rear_steer]


def _triple(row: Sequence[float], start: int) -> Vector:
    return (row[start], row[start + 1], row[start + 2])


class EgoTrack:
    """EgoVehicleStatus messages; every field interpolated, the heading along the shorter arc."""

    # Columns: position 0-2, velocity 3-5, acceleration 6-8, heading 9 (unwrapped rad),
    # accel pedal 10, brake pedal 11, front steer 12 (rad), rear steer 13 (rad).
    def __init__(self, times: np.ndarray, unique_ids: np.ndarray, columns: np.ndarray) -> None:
        self.times = times
        self.unique_ids = unique_ids
        self.columns = columns

    @classmethod
    def from_messages(cls, times: np.ndarray, messages: Sequence[EgoStatus]) -> EgoTrack:
        rows = [
            [
                *_vector(m.position),
                *_vector(m.velocity),
                *_vector(m.acceleration),
                m.heading,
                m.accel,
                m.brake,
                *_ego_steer(m),
            ]
            for m in messages
        ]
        columns = np.array(rows, dtype=np.float64).reshape(len(rows), 14)
        columns[:, [9, 12, 13]] = np.radians(columns[:, [9, 12, 13]])
        # Unwrapped, a straight interpolation between rows follows the shorter arc.
        columns[:, 9] = np.unwrap(columns[:, 9])
        unique_ids = np.array([m.unique_id for m in messages], dtype=np.int64)
        return cls(times, unique_ids, columns)

    def __len__(self) -> int:
        return len(self.times)

    def sample(self, t: float) -> EgoState:
        i, j, alpha = _bracket(self.times, t)
        row = self.columns[i] + alpha * (self.columns[j] - self.columns[i])
        values = row.tolist()
        return EgoState(
            unique_id=int(self.unique_ids[i]),
            position=_triple(values, 0),
            heading=float(_wrap(values[9])),
            velocity=_triple(values, 3),
            acceleration=_triple(values, 6),
            accel_pedal=values[10],
            brake_pedal=values[11],
            front_steer=values[12],
            rear_steer=values[13],
        )


class ObjectTrack:
    """ObjectStatusList messages, flattened: message k owns rows offsets[k]:offsets[k+1].

    A sample gives the objects of the latest message at or before t; an object
    that the next message lists too (same list, same unique_id) is interpolated
    towards it.
    """

    # Columns: position 0-2, velocity 3-5 (m/s), acceleration 6-8, size 9-11, heading 12 (rad).
    def __init__(
        self,
        times: np.ndarray,
        offsets: np.ndarray,
        keys: np.ndarray,
        kinds: np.ndarray,
        names: list[str],
        columns: np.ndarray,
    ) -> None:
        self.times = times
        self.offsets = offsets
        self.keys = keys  # unique_id * 4 + list index: ids are matched within a list only
        self.kinds = kinds  # (list index, protocol type) per row
        self.names = names
        self.columns = columns
        # Interpolation pairs objects by id, which is only sound when ids are unique.
        self.unique_keys = _messages_with_unique_keys(offsets, keys)
        # Building a sample's objects walks rows one by one: plain lists index faster.
        self._row_ids = (keys // 4).tolist()
        self._row_kinds = kinds.tolist()

    @classmethod
    def from_messages(cls, times: np.ndarray, messages: Sequence[ObjectList]) -> ObjectTrack:
        offsets = [0]
        keys: list[int] = []
        kinds: list[tuple[int, int]] = []
        names: list[str] = []
        rows: list[list[float]] = []
        for message in messages:
            # the category of an object: its list's place in a frame
            lists = (message.npc_list, message.pedestrian_list, message.obstacle_list)
            for category, objects in enumerate(lists):
                for obj in objects:
                    keys.append(obj.unique_id * 4 + category)
                    kinds.append((category, obj.type))
                    names.append(obj.name)
                    rows.append(
                        [
                            *_vector(obj.position),
                            *_vector(obj.velocity),
                            *_vector(obj.acceleration),
                            *_vector(obj.size),
                            obj.heading,
                        ]
                    )
            offsets.append(len(rows))
        columns = np.array(rows, dtype=np.float64).reshape(len(rows), 13)
        columns[:, 3:6] *= KMH_TO_MS
        columns[:, 12] = _wrap(np.radians(columns[:, 12]))
        return cls(
            times,
            np.array(offsets, dtype=np.int64),
            np.array(keys, dtype=np.int64),
            np.array(kinds, dtype=np.int64).reshape(len(kinds), 2),
            names,
            columns,
        )

    def __len__(self) -> int:
        return len(self.times)

    def sample(self, t: float) -> tuple[tuple[ObjectState, ...], ...]:
        """(npcs, pedestrians, obstacles) at `t`; empty before the first message."""
        if not len(self.times) or t < self.times[0]:
            return ((), (), ())
        i, j, alpha = _bracket(self.times, t)
        start, stop = int(self.offsets[i]), int(self.offsets[i + 1])
        rows = self.columns[start:stop].copy()
        if alpha > 0 and self.unique_keys[i] and self.unique_keys[j]:
            following = slice(self.offsets[j], self.offsets[j + 1])
            _, here, there = np.intersect1d(
                self.keys[start:stop], self.keys[following], assume_unique=True, return_indices=True
            )
            delta = self.columns[following][there] - rows[here]
            delta[:, 12] = _wrap(delta[:, 12])
            rows[here] += alpha * delta
            rows[here, 12] = _wrap(rows[here, 12])
        lists: tuple[list[ObjectState], ...] = ([], [], [])
        for unique_id, (category, type_code), name, values in zip(
            self._row_ids[start:stop],
            self._row_kinds[start:stop],
            self.names[start:stop],
            rows.tolist(),
            strict=True,
        ):
            lists[category].append(
                ObjectState(
                    unique_id=unique_id,
                    type=type_code,
                    name=name,
                    position=(values[0], values[1], values[2]),
                    heading=values[12],
                    velocity=(values[3], values[4], values[5]),
                    acceleration=(values[6], values[7], values[8]),
                    size=(values[9], values[10], values[11]),
                )
            )
        return tuple(tuple(objects) for objects in lists)


def _messages_with_unique_keys(offsets: np.ndarray, keys: np.ndarray) -> np.ndarray:
    """Per message, whether no key repeats within it."""
    message_count = len(offsets) - 1
    owner = np.repeat(np.arange(message_count), np.diff(offsets))
    order = np.lexsort((keys, owner))
    sorted_keys, sorted_owner = keys[order], owner[order]
    repeated = (sorted_keys[1:] == sorted_keys[:-1]) & (sorted_owner[1:] == sorted_owner[:-1])
    unique = np.ones(message_count, dtype=bool)
    unique[sorted_owner[1:][repeated]] = False
    return unique


class ControlTrack:
    """CtrlCmd messages; a command holds until the next one, so it is not interpolated."""

    # Columns: mode 0, accel 1, brake 2, front steer 3 (rad), rear steer 4 (rad),
    # velocity 5 (m/s), acceleration 6.
    def __init__(self, times: np.ndarray, columns: np.ndarray) -> None:
        self.times = times
        self.columns = columns

    @classmethod
    def from_messages(cls, times: np.ndarray, messages: Sequence[CtrlCmd]) -> ControlTrack:
        rows = [
            [
                m.longlCmdType,
                m.accel,
                m.brake,
                *_command_steer(m),
                m.velocity * KMH_TO_MS,
                m.acceleration,
            ]
            for m in messages
        ]
        return cls(times, np.array(rows, dtype=np.float64).reshape(len(rows), 7))

    def __len__(self) -> int:
        return len(self.times)

    def sample(self, t: float) -> ControlCommand | None:
        """The command in force at `t`; None before the first one."""
        if not len(self.times) or t < self.times[0]:
            return None
        i = int(np.searchsorted(self.times, t, side="right")) - 1
        mode, accel, brake, front, rear, velocity, acceleration = self.columns[i].tolist()
        return ControlCommand(int(mode), accel, brake, front, rear, velocity, acceleration)
