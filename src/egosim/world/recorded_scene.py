"""A recorded scene the world shows in place of its own simulation (rosbag replay).

While a scene is shown, each kind it holds is taken from the recording instead
of being simulated: the main ego is placed at the recorded pose every step, and
the recorded NPC, pedestrian and obstacle tables stand in for the simulated
agents of those kinds, which wait, frozen, until the scene is withdrawn. Kinds
the scene leaves out (None) keep being simulated and react to the recorded ones.
"""

from __future__ import annotations

from dataclasses import dataclass

from egosim.world.traffic import ObjectTable
from egosim.world.vehicle import Pose


@dataclass(frozen=True)
class RecordedEgo:
    """The main ego as recorded: pose, speed along its body x (m/s), wheel angles (rad),
    and what placing a vehicle cannot reproduce: its body-frame acceleration (m/s²) and
    the pedals (0..1) it had."""

    pose: Pose
    speed: float
    front_steer: float
    rear_steer: float
    acceleration: tuple[float, float, float] = (0.0, 0.0, 0.0)
    accel_pedal: float = 0.0
    brake_pedal: float = 0.0


@dataclass(frozen=True, eq=False)
class RecordedScene:
    ego: RecordedEgo | None = None
    npcs: ObjectTable | None = None
    pedestrians: ObjectTable | None = None
    obstacles: ObjectTable | None = None
