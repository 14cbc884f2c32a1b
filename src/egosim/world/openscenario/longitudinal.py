"""Longitudinal actions while they run: SpeedAction, SpeedProfileAction,
LongitudinalDistanceAction and SynchronizeAction."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

from egosim.world.openscenario.dynamics import duration_at_rate, progress
from egosim.world.openscenario.entities import EntityState
from egosim.world.openscenario.motion import MotionRun
from egosim.world.openscenario.runtime import Runtime

SPEED_REACHED_MPS = 1e-6


@dataclass(frozen=True)
class SpeedTarget:
    """AbsoluteTargetSpeed (entity empty) or RelativeTargetSpeed to `entity`'s speed:
    `delta` (value added) or `factor` (value times); continuous: follow it after."""

    value: float
    entity: str = ""
    value_type: str = "delta"
    continuous: bool = False

    def speed(self, rt: Runtime) -> float:
        if not self.entity:
            return self.value
        reference = rt.entity(self.entity).speed
        return reference * self.value if self.value_type == "factor" else reference + self.value


class SpeedRun(MotionRun):
    """From the speed it has to the target, along the shape, over the time, the distance
    or at the rate the dynamics name."""

    longitudinal = True

    def __init__(self, target: SpeedTarget, shape: str, dimension: str, value: float) -> None:
        super().__init__()
        self.target = target
        self.shape = shape
        self.dimension = dimension
        self.value = value
        self.elapsed = 0.0
        self.start_speed = math.nan
        self.duration = math.nan

    def begin(self, rt: Runtime, entity: EntityState) -> None:
        super().begin(rt, entity)
        self.start_speed = entity.speed
        if self.target.entity == entity.name:
            # Relative to itself: to its speed of now plus the delta (a target that
            # moved with its own speed could never be reached).
            self.target = SpeedTarget(self.target.speed(rt))
        change = self.target.speed(rt) - self.start_speed
        if self.shape == "step":
            self.duration = 0.0
        elif self.dimension == "time":
            self.duration = max(self.value, 0.0)
        elif self.dimension == "distance":
            # The shapes are symmetric: the mean speed is the mid speed.
            mean = abs(self.start_speed + self.target.speed(rt)) / 2.0
            self.duration = self.value / mean if mean > 0 else 0.0
        else:
            self.duration = duration_at_rate(self.shape, change, self.value)
        if self.duration <= 0.0:
            # A step takes effect at once (later Init actions see the new speed).
            entity.speed = self.target.speed(rt)

    def speed(self, rt: Runtime, entity: EntityState, dt: float) -> float:
        self.elapsed += dt
        target = self.target.speed(rt)
        if self.duration <= 0.0 or self.elapsed >= self.duration - 1e-9:
            self.done = not self.target.continuous
            return target
        fraction = self.elapsed / self.duration
        return self.start_speed + (target - self.start_speed) * progress(self.shape, fraction)


class SpeedProfileRun(MotionRun):
    """SpeedProfileAction: piecewise-linear speed through its entries (each `time` s
    after the one before, or the time the dynamics allow when it has none)."""

    longitudinal = True

    def __init__(
        self,
        entries: list[tuple[float, float | None]],
        entity: str,
        max_acceleration: float,
    ) -> None:
        super().__init__()
        self.entries = entries
        self.entity = entity
        self.max_acceleration = max_acceleration
        self.elapsed = 0.0
        self.knots: list[tuple[float, float]] = []

    def begin(self, rt: Runtime, entity: EntityState) -> None:
        super().begin(rt, entity)
        base = rt.entity(self.entity).speed if self.entity else 0.0
        t, v = 0.0, entity.speed
        self.knots = [(t, v)]
        for speed, time in self.entries:
            target = base + speed
            step = time if time is not None else abs(target - v) / max(self.max_acceleration, 1e-9)
            t += max(step, 0.0)
            v = target
            self.knots.append((t, v))

    def speed(self, rt: Runtime, entity: EntityState, dt: float) -> float:
        self.elapsed += dt
        times = [k[0] for k in self.knots]
        speeds = [k[1] for k in self.knots]
        if self.elapsed >= times[-1]:
            self.done = True
            return speeds[-1]
        for k in range(1, len(times)):
            if self.elapsed <= times[k]:
                span = times[k] - times[k - 1]
                f = (self.elapsed - times[k - 1]) / span if span > 0 else 1.0
                return speeds[k - 1] + f * (speeds[k] - speeds[k - 1])
        return speeds[-1]


Gap = Callable[[Runtime, EntityState], float | None]
"""The distance (m) still to close: positive while the entity must gain on its target."""


class DistanceRun(MotionRun):
    """LongitudinalDistanceAction: without dynamic limits the entity is put at the
    distance at once (and, continuous, kept there moving with the target); with them it
    closes the gap as fast as they allow."""

    longitudinal = True

    def __init__(
        self,
        gap: Gap,
        reference: str,
        continuous: bool,
        jump: Callable[[Runtime, EntityState], bool],
        max_acceleration: float,
        max_deceleration: float,
        max_speed: float,
    ) -> None:
        super().__init__()
        self.gap = gap
        self.reference = reference
        self.continuous = continuous
        self.jump = jump
        self.limits = (max_acceleration, max_deceleration, max_speed)
        self.limited = math.isfinite(max_acceleration) or math.isfinite(max_deceleration)

    def begin(self, rt: Runtime, entity: EntityState) -> None:
        super().begin(rt, entity)
        if not self.limited and self.jump(rt, entity):
            entity.speed = rt.entity(self.reference).speed
            self.done = not self.continuous

    def speed(self, rt: Runtime, entity: EntityState, dt: float) -> float:
        reference = rt.entity(self.reference).speed
        gap = self.gap(rt, entity)
        if gap is None:
            return entity.speed
        if not self.limited:
            if self.continuous:
                self.jump(rt, entity)
                return reference
            self.done = True
            return entity.speed
        accel, decel, top = self.limits
        # Close the gap with a braking curve the limits allow, then match the target.
        wanted = reference + math.copysign(math.sqrt(2.0 * min(accel, decel) * abs(gap)), gap)
        wanted = min(max(wanted, -top), top)
        change = wanted - entity.speed
        change = min(max(change, -decel * dt), accel * dt)
        if abs(gap) < 0.05 and abs(entity.speed - reference) < 0.05:
            self.done = not self.continuous
        return entity.speed + change


Distance = Callable[[Runtime, EntityState], float | None]
"""Distance (m) from an entity to its target position along the way it goes."""


class SynchronizeRun(MotionRun):
    """SynchronizeAction: the entity reaches its target when the master reaches the
    master's, at the final speed if one is given (held over the steady-state distance or
    time before the target).

    The speed stays continuous: every step it follows the one speed profile that starts
    at the speed it has, covers the distance to go in the master's time to go and ends
    at the final speed, v(t) = v0 + (vf - v0) t/T + k t (T - t) with
    k = 6 (D - (v0 + vf) T / 2) / T³ (its acceleration changes linearly). Without a
    final speed it ends at the mean speed D/T. It is planned afresh each step, so it
    follows a master that changes speed."""

    longitudinal = True

    def __init__(
        self,
        master: str,
        master_distance: Distance,
        own_distance: Distance,
        final_speed: Callable[[Runtime], float] | None,
        steady_distance: float,
        steady_time: float,
        tolerance: float,
        master_tolerance: float,
    ) -> None:
        super().__init__()
        self.master = master
        self.master_distance = master_distance
        self.own_distance = own_distance
        self.final_speed = final_speed
        self.steady_distance = steady_distance
        self.steady_time = steady_time
        self.tolerance = tolerance
        self.master_tolerance = master_tolerance

    def speed(self, rt: Runtime, entity: EntityState, dt: float) -> float:
        master = rt.entity(self.master)
        to_master_target = self.master_distance(rt, master)
        to_target = self.own_distance(rt, entity)
        if to_master_target is None or to_target is None:
            return entity.speed
        # A master reversing to its target (Euro NCAP's CPRA) closes in as fast.
        master_speed = abs(master.speed)
        # Done in the step the master gets there (the action ends as it arrives).
        if to_master_target - master_speed * dt <= self.master_tolerance or (
            to_target <= self.tolerance
        ):
            self.done = True
            return self.final_speed(rt) if self.final_speed is not None else entity.speed
        if master_speed <= SPEED_REACHED_MPS:
            return entity.speed if self.final_speed is None else 0.0
        time_left = to_master_target / master_speed
        if self.final_speed is None:
            return _continuous_profile(
                entity.speed, to_target / time_left, to_target, time_left, dt
            )
        final = self.final_speed(rt)
        steady = self.steady_distance
        if self.steady_time > 0.0:
            steady = final * self.steady_time
        distance = to_target - steady
        time = time_left - (steady / final if final > 0 else 0.0)
        if distance <= 0.0 or time <= dt:
            return final
        return _continuous_profile(entity.speed, final, distance, time, dt)


def _continuous_profile(v0: float, vf: float, distance: float, time: float, dt: float) -> float:
    """The speed dt s into the profile from v0 to vf that covers `distance` in `time`
    (never below standstill)."""
    if time <= dt:
        return vf
    k = 6.0 * (distance - (v0 + vf) * time / 2.0) / time**3
    return max(v0 + (vf - v0) * dt / time + k * dt * (time - dt), 0.0)
