"""What a replay gives at one instant: ego state, surrounding objects, the ego's command.

SI units throughout (m, s, rad, m/s); the protocol's degrees and km/h are
converted when a bag is read and again by the bridge when it publishes.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

Vector = tuple[float, float, float]


@dataclass(frozen=True)
class EgoState:
    """The ego vehicle as /Ego_topic (EgoVehicleStatus) recorded it."""

    unique_id: int
    position: Vector  # m, ENU map frame
    heading: float  # rad, ENU (0 = east, counter-clockwise), in (-pi, pi]
    velocity: Vector  # m/s, vehicle frame
    acceleration: Vector  # m/s^2
    accel_pedal: float  # 0..1
    brake_pedal: float  # 0..1
    front_steer: float  # rad, front wheel angle
    rear_steer: float  # rad, rear wheel angle


@dataclass(frozen=True)
class ObjectState:
    """One entry of an ObjectStatusList (NPC vehicle, pedestrian or obstacle)."""

    unique_id: int
    type: int  # protocol code: 0 pedestrian, 1 NPC vehicle, 2 static obstacle
    name: str
    position: Vector  # m, ENU map frame
    heading: float  # rad, in (-pi, pi]
    velocity: Vector  # m/s (the protocol sends km/h)
    acceleration: Vector  # m/s^2
    size: Vector  # m, as ObjectStatus lists it: width, length, height


@dataclass(frozen=True)
class ControlCommand:
    """The ego's CtrlCmd in force (the latest received), as /ctrl_cmd carried it."""

    longitudinal_mode: int  # longlCmdType: 1 pedals, 2 target velocity, 3 target acceleration
    accel_pedal: float  # 0..1
    brake_pedal: float  # 0..1
    front_steer: float  # rad
    rear_steer: float  # rad
    velocity: float  # m/s target (the protocol sends km/h)
    acceleration: float  # m/s^2 target


@dataclass(frozen=True)
class ReplayFrame:
    """The recorded scene at `time` s after the bag's start."""

    time: float  # s from the bag's start
    stamp_ns: int  # the same instant on the bag's own clock (header stamps), ns
    ego: EgoState | None
    npcs: tuple[ObjectState, ...] = ()
    pedestrians: tuple[ObjectState, ...] = ()
    obstacles: tuple[ObjectState, ...] = ()
    control: ControlCommand | None = None

    def restricted(self, *, ego: bool, npcs: bool, pedestrians: bool) -> ReplayFrame:
        """This frame with the unselected replay targets removed.

        Static obstacles go with the NPC vehicles: the protocol's targets name
        only ego, NPC vehicles and pedestrians. The ego's command goes with the ego.
        """
        return replace(
            self,
            ego=self.ego if ego else None,
            control=self.control if ego else None,
            npcs=self.npcs if npcs else (),
            obstacles=self.obstacles if npcs else (),
            pedestrians=self.pedestrians if pedestrians else (),
        )
