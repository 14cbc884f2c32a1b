"""Multi-ego: MultiEgoSetting sets how many egos there are, where, and how they are driven.

Egos are numbered by their position in the world's list: 0 is the main ego (the
un-namespaced rows), 1, 2, ... the additional ones. ego_index[i] names the ego that
entry i of every per-ego array configures, and camera_index the ego /Ego_topic
reports. Ego k >= 1 is observable on /ego_<k>/Ego_topic and controllable on
/ego_<k>/ctrl_cmd (the effective names of the ego_status and ctrl_cmd rows under
/ego_<k>), advertised when the ego appears and withdrawn when it is removed.

Every per-ego array is either empty (that attribute is left as it is) or has one
entry per ego_index. Units: position m, roll/pitch/yaw deg, velocity and
vehicle_speed km/h, steering_angle deg. An ego's brake lights follow its brakes, so
brake_light is checked for length only. A message with any error is logged and
ignored as a whole. The details are in docs/protocol.md.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Callable
from typing import TYPE_CHECKING

from ...world.vehicle import Gear, Pose
from ..context import BridgeContext, RowBinder
from ..ego_session import Lamps
from ..protocol.codes import ControlMode
from ..protocol.table import Row
from ..protocol.units import mps, rad
from .ego import drive_with_ctrl_cmd, ego_status_of

if TYPE_CHECKING:
    from ...msgs.typed import morai_26_r1

log = logging.getLogger(__name__)

# MultiEgoSetting.ctrl_mode: the document's 1 keyboard and 16 auto, and EventInfo's codes
# (2 gamepad, 3 external, 4 auto), which collide with neither.
MULTI_EGO_AUTO = 16
CTRL_MODES = {**{int(mode): mode for mode in ControlMode}, MULTI_EGO_AUTO: ControlMode.AUTO}
# MultiEgoSetting.turn_signal -> Lamps (turnSignal, emergencySignal).
TURN_SIGNAL_LAMPS = {0: Lamps(0, 0), 1: Lamps(1, 0), 2: Lamps(2, 0), 3: Lamps(0, 1)}
FLOAT_ARRAYS = (
    "global_position_x",
    "global_position_y",
    "global_position_z",
    "global_roll",
    "global_pitch",
    "global_yaw",
    "velocity",
    "steering_angle",
    "vehicle_speed",
)
"""The arrays that move an ego (a teleport)."""
PER_EGO_ARRAYS = (*FLOAT_ARRAYS, "gear", "ctrl_mode", "turn_signal", "brake_light")

Entry = dict[str, float]
"""One ego's attributes, by the name of the array that gave each (all of them numbers)."""


class SettingError(ValueError):
    """Why a MultiEgoSetting message cannot be applied."""


def ego_namespace(k: int) -> str:
    return f"/ego_{k}"


def on_multi_ego_setting(
    context: BridgeContext, row: Row, message: morai_26_r1.MultiEgoSetting
) -> None:
    """/ego_setting: check the whole message, then apply it."""
    try:
        entries = _entries(message, len(context.world.egos))
    except SettingError as error:
        log.error("%s ignored: %s", row.name, error)
        return
    world = context.world
    world.keep_egos(message.number_of_ego_vehicle)
    model = world.egos[0].vehicle.model
    for k, entry in sorted(entries.items()):
        if k >= len(world.egos):
            world.add_ego(model, _pose(entry, None))
        _apply(context, k, entry, row.name)
    context.session.camera_index = int(message.camera_index)
    _sync_ego_rows(context)


def _entries(message: morai_26_r1.MultiEgoSetting, existing: int) -> dict[int, Entry]:
    """Each configured ego's attributes by position, checked."""
    count = int(message.number_of_ego_vehicle)
    if count < 1:
        raise SettingError(f"number_of_ego_vehicle {count}: the main ego always exists")
    if not 0 <= message.camera_index < count:
        raise SettingError(f"camera_index {message.camera_index} is not an ego (0..{count - 1})")
    indices = [int(i) for i in _values(message, "ego_index")]
    arrays = {name: _values(message, name) for name in PER_EGO_ARRAYS}
    for name, values in arrays.items():
        if len(values) not in (0, len(indices)):
            raise SettingError(f"{name} has {len(values)} entries for {len(indices)} egos")
    if len(set(indices)) != len(indices) or not all(0 <= i < count for i in indices):
        raise SettingError(f"ego_index {indices} must name distinct egos 0..{count - 1}")
    for name in FLOAT_ARRAYS:
        if not all(math.isfinite(v) for v in arrays[name]):
            raise SettingError(f"{name} holds a non-finite value")
    if len(arrays["global_position_x"]) != len(arrays["global_position_y"]):
        raise SettingError("global_position_x and global_position_y come together")
    entries = {
        k: {name: values[i] for name, values in arrays.items() if values}
        for i, k in enumerate(indices)
    }
    for k in range(existing, count):
        if "global_position_x" not in entries.get(k, {}):
            raise SettingError(f"new ego {k} needs a position (list it in ego_index)")
    for k, entry in entries.items():
        if "gear" in entry and entry["gear"] not in Gear.__members__.values():
            raise SettingError(f"ego {k}: gear {entry['gear']} is not 1..4")
        if "ctrl_mode" in entry and entry["ctrl_mode"] not in CTRL_MODES:
            raise SettingError(f"ego {k}: ctrl_mode {entry['ctrl_mode']} is not 1..4 or 16")
        if "turn_signal" in entry and entry["turn_signal"] not in TURN_SIGNAL_LAMPS:
            raise SettingError(f"ego {k}: turn_signal {entry['turn_signal']} is not 0..3")
    return entries


def _values(message: morai_26_r1.MultiEgoSetting, name: str) -> list[float]:
    """A message array as plain Python numbers (the decoder may give a numpy array)."""
    values = getattr(message, name)
    return values.tolist() if hasattr(values, "tolist") else list(values)


def _pose(entry: Entry, current: Pose | None) -> Pose:
    """The entry's pose; attributes it leaves out keep `current`'s (0 for a new ego)."""
    current = current or Pose()
    return Pose(
        entry.get("global_position_x", current.x),
        entry.get("global_position_y", current.y),
        entry.get("global_position_z", current.z),
        rad(entry["global_roll"]) if "global_roll" in entry else current.roll,
        rad(entry["global_pitch"]) if "global_pitch" in entry else current.pitch,
        rad(entry["global_yaw"]) if "global_yaw" in entry else current.yaw,
    )


def _apply(context: BridgeContext, k: int, entry: Entry, by: str) -> None:
    ego = context.world.egos[k]
    vehicle = ego.vehicle
    status = vehicle.status()
    moved = any(name in entry for name in FLOAT_ARRAYS)
    if moved:
        speed_kmh = entry.get("velocity", entry.get("vehicle_speed"))
        speed = status.velocity[0] if speed_kmh is None else mps(speed_kmh)
        steer = rad(entry["steering_angle"]) if "steering_angle" in entry else status.front_steer
        vehicle.teleport(_pose(entry, status.pose), speed, steer)
    if "gear" in entry:
        vehicle.set_gear(Gear(int(entry["gear"])))
    session = context.ego_session(ego)
    if "ctrl_mode" in entry:
        session.set_ctrl_mode(CTRL_MODES[int(entry["ctrl_mode"])], by=by)
    if "turn_signal" in entry:
        session.set_lamps(TURN_SIGNAL_LAMPS[int(entry["turn_signal"])])


def _sync_ego_rows(context: BridgeContext) -> None:
    """Open the namespaced rows of egos that appeared; the sessions of egos removed go,
    closing theirs."""
    egos = context.world.egos
    context.session.egos.keep(egos)
    if context.rows is None:
        return
    for k, ego in enumerate(egos[1:], start=1):
        session = context.ego_session(ego)
        if not session.has_rows:
            session.open_rows(_open_ego_rows(context.rows, k))


def _open_ego_rows(rows: RowBinder, k: int) -> list[Callable[[], None]]:
    namespace = ego_namespace(k)
    closers = [
        rows.open_publisher("ego_status", namespace, lambda ctx, row: ego_status_of(ctx, k)),
        rows.open_subscriber(
            "ctrl_cmd",
            namespace,
            lambda profile: profile.message("morai_msgs/CtrlCmd"),
            lambda ctx, row, msg: drive_with_ctrl_cmd(ctx, row, k, msg),
        ),
    ]
    return [close for close in closers if close is not None]
