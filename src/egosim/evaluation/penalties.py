"""The driving score: route completion times the product of one coefficient per infraction."""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping

from egosim.evaluation.infractions import Infraction, InfractionKind

CARLA_LEADERBOARD_1_PENALTIES: Mapping[InfractionKind, float] = {
    InfractionKind.COLLISION_PEDESTRIAN: 0.50,
    InfractionKind.COLLISION_VEHICLE: 0.60,
    InfractionKind.COLLISION_STATIC: 0.65,
    InfractionKind.RED_LIGHT: 0.70,
    InfractionKind.STOP_LINE: 0.80,
}
"""CARLA leaderboard 1.0's multiplicative coefficients; every other kind counts 1.0 (it is
reported and may fail a criterion, but leaves the score alone) unless configured."""


def penalty_factor(
    infractions: Iterable[Infraction],
    coefficients: Mapping[InfractionKind, float] = CARLA_LEADERBOARD_1_PENALTIES,
) -> float:
    """Product over the infractions of their kind's coefficient (1.0 for none)."""
    return math.prod(coefficients.get(infraction.kind, 1.0) for infraction in infractions)


def driving_score(
    route_completion: float | None,
    infractions: Iterable[Infraction],
    coefficients: Mapping[InfractionKind, float] = CARLA_LEADERBOARD_1_PENALTIES,
) -> float:
    """route_completion (0..1) x penalty factor; without a route, the penalty factor alone."""
    completion = 1.0 if route_completion is None else route_completion
    return completion * penalty_factor(infractions, coefficients)
