"""DriveEvaluator: watches the main ego of a World step by step and scores the drive."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import TypedDict

from egosim.evaluation.comfort import comfort_figures, lane_error_figures
from egosim.evaluation.infractions import (
    COLLISION_KINDS,
    Infraction,
    InfractionKind,
    InfractionRecord,
)
from egosim.evaluation.lead import lead_gap
from egosim.evaluation.penalties import CARLA_LEADERBOARD_1_PENALTIES, driving_score, penalty_factor
from egosim.evaluation.route import Route, RouteProgress
from egosim.evaluation.rules import Sample
from egosim.evaluation.watch import DEFAULT_BLOCKED_AFTER_S, InfractionWatch, ego_sample
from egosim.world import World

TRAJECTORY_PERIOD_S = 0.1
"""The trajectory kept for reports is sampled this often."""


@dataclass(frozen=True)
class EvaluationSettings:
    penalties: Mapping[InfractionKind, float] = field(
        default_factory=lambda: dict(CARLA_LEADERBOARD_1_PENALTIES)
    )
    """Coefficient of each infraction kind in the driving score (missing kinds: 1.0)."""
    blocked_after_s: float = DEFAULT_BLOCKED_AFTER_S
    lane_departure_margin_m: float = 0.0
    """The body may reach this far over its lane's boundary before it counts."""
    safety_period_s: float = 0.05
    """Time-to-collision and headway are sampled this often (each sample scans every
    object); everything else is watched at every step."""


Metrics = dict[str, float | int | None]
"""A drive's figures by name (flat, JSON-ready; None: not measured)."""


class ScoreRecord(TypedDict):
    """A DriveScore as JSON (score.json)."""

    metrics: Metrics
    infractions: list[InfractionRecord]
    trajectory: list[list[float]]
    """[t s, x m, y m, speed m/s] rows."""


@dataclass(frozen=True)
class DriveScore:
    """A scored drive: the figures (flat, JSON-ready), the infractions, the trajectory."""

    metrics: Metrics
    infractions: tuple[Infraction, ...]
    trajectory: tuple[tuple[float, float, float, float], ...]
    """(t s, x m, y m, speed m/s) every TRAJECTORY_PERIOD_S."""

    def as_dict(self) -> ScoreRecord:
        return {
            "metrics": dict(self.metrics),
            "infractions": [i.as_dict() for i in self.infractions],
            "trajectory": [[round(v, 3) for v in point] for point in self.trajectory],
        }


class DriveEvaluator:
    """Call observe(world) after every world step; score(...) at the end of the drive.

    Reads the world only (its ego, lanes, lights, objects and collision log), so it gives
    the same score for the same drive whoever runs it.
    """

    def __init__(
        self, world: World, route: Route | None = None, settings: EvaluationSettings | None = None
    ) -> None:
        self.settings = settings or EvaluationSettings()
        self._route = None if route is None else RouteProgress(route)
        self._watch = InfractionWatch(
            world,
            blocked_after_s=self.settings.blocked_after_s,
            lane_departure_margin_m=self.settings.lane_departure_margin_m,
        )
        self._times: list[float] = []
        self._long: list[float] = []
        self._lat: list[float] = []
        self._lane_errors: list[float] = []
        self._trajectory: list[tuple[float, float, float, float]] = []
        self._distance_m = 0.0
        self._last_xy: tuple[float, float] | None = None
        self._min_ttc: float | None = None
        self._min_headway: float | None = None
        self._start_s: float | None = None
        self._next_safety_s = -math.inf

    @property
    def finish_reason(self) -> str | None:
        """Why the drive is over whatever the time ("route_completed", "blocked"), else None."""
        if self._watch.blocked:
            return "blocked"
        if self._route is not None and self._route.completed:
            return "route_completed"
        return None

    @property
    def finished(self) -> bool:
        return self.finish_reason is not None

    def observe(self, world: World) -> None:
        """Take one sample of the main ego (call after each step of the world)."""
        sample = ego_sample(world)
        self._watch.observe(world, sample)
        if self._start_s is None:
            self._start_s = sample.time_s
        if self._route is not None:
            self._route.update(sample.x, sample.y)
        self._kinematics(world, sample)

    def _kinematics(self, world: World, sample: Sample) -> None:
        status = world.ego_status(0)
        self._times.append(sample.time_s)
        self._long.append(status.acceleration[0])
        self._lat.append(status.acceleration[1])
        self._lane_errors.append(sample.lateral_m)
        if self._last_xy is not None:
            self._distance_m += math.hypot(sample.x - self._last_xy[0], sample.y - self._last_xy[1])
        self._last_xy = (sample.x, sample.y)
        last = self._trajectory[-1][0] if self._trajectory else -math.inf
        if sample.time_s - last >= TRAJECTORY_PERIOD_S - 1e-9:
            self._trajectory.append((sample.time_s, sample.x, sample.y, sample.speed_mps))
        if sample.time_s < self._next_safety_s:
            return
        self._next_safety_s = sample.time_s + self.settings.safety_period_s - 1e-9
        gap = lead_gap(world.objects(), world.egos[0].unique_id)
        if gap is not None:
            self._min_ttc = _least(self._min_ttc, gap.ttc_s)
            self._min_headway = _least(self._min_headway, gap.headway_s)

    def infractions(self, *, timed_out: bool = False) -> list[Infraction]:
        """Every infraction so far, by time; `timed_out` adds the time-out of a route not
        completed."""
        found = self._watch.records()
        if timed_out and self._route is not None and not self._route.completed:
            t, x, y, _ = self._trajectory[-1] if self._trajectory else (0.0, 0.0, 0.0, 0.0)
            detail = f"route {self._route.completion:.0%} driven when time ran out"
            found.append(Infraction(InfractionKind.TIMEOUT, t, x, y, detail))
        return sorted(found, key=lambda i: (i.time_s, i.kind.value))

    def score(self, *, timed_out: bool = False) -> DriveScore:
        """The drive so far; `timed_out`: it ended at the time limit."""
        infractions = self.infractions(timed_out=timed_out)
        completion = None if self._route is None else self._route.completion
        penalties = self.settings.penalties
        duration = self._times[-1] - (self._start_s or 0.0) if self._times else 0.0
        metrics: dict[str, float | int | None] = {
            "route_completion": completion,
            "route_length_m": None if self._route is None else self._route.route.length,
            "driving_score": driving_score(completion, infractions, penalties),
            "infraction_penalty": penalty_factor(infractions, penalties),
            "infractions": len(infractions),
            "collisions": sum(i.kind in COLLISION_KINDS for i in infractions),
            **{
                f"{kind.value}_count": sum(i.kind is kind for i in infractions)
                for kind in InfractionKind
            },
            "duration_s": duration,
            "distance_m": self._distance_m,
            "min_ttc_s": self._min_ttc,
            "min_headway_s": self._min_headway,
            **comfort_figures(self._times, self._long, self._lat),
            **lane_error_figures(self._lane_errors),
        }
        return DriveScore(metrics, tuple(infractions), tuple(self._trajectory))


METRIC_NAMES = frozenset(
    {
        "route_completion",
        "route_length_m",
        "driving_score",
        "infraction_penalty",
        "infractions",
        "collisions",
        *(f"{kind.value}_count" for kind in InfractionKind),
        "duration_s",
        "distance_m",
        "min_ttc_s",
        "min_headway_s",
        *comfort_figures([], [], []),
        *lane_error_figures([]),
    }
)
"""Every figure a DriveScore holds (what criteria may name)."""


def _least(known: float | None, value: float | None) -> float | None:
    if value is None:
        return known
    return value if known is None else min(known, value)
