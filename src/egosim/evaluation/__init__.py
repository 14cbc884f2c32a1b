"""Scoring a drive from the world, in-process and pure (no I/O, no ROS).

Public API:
    DriveEvaluator, EvaluationSettings, DriveScore, METRIC_NAMES   observe a world, score it
    Metrics, ScoreRecord                                           a score as JSON
    Infraction, InfractionKind, InfractionRecord                   what went wrong, when, where
    InfractionWatch, ego_sample                                    one ego's, as they begin
    Route, RouteError                                              the route to drive
    CARLA_LEADERBOARD_1_PENALTIES, driving_score, penalty_factor   the driving score
    Criterion, CriterionResult, CriterionError, parse_criterion    pass criteria
    CriterionRecord                                                a checked criterion as JSON
"""

from egosim.evaluation.criteria import (
    Criterion,
    CriterionError,
    CriterionRecord,
    CriterionResult,
    parse_criterion,
)
from egosim.evaluation.evaluator import (
    METRIC_NAMES,
    DriveEvaluator,
    DriveScore,
    EvaluationSettings,
    Metrics,
    ScoreRecord,
)
from egosim.evaluation.infractions import (
    COLLISION_KINDS,
    Infraction,
    InfractionKind,
    InfractionRecord,
)
from egosim.evaluation.penalties import CARLA_LEADERBOARD_1_PENALTIES, driving_score, penalty_factor
from egosim.evaluation.route import Route, RouteError
from egosim.evaluation.watch import InfractionWatch, ego_sample

__all__ = [
    "CARLA_LEADERBOARD_1_PENALTIES",
    "COLLISION_KINDS",
    "METRIC_NAMES",
    "Criterion",
    "CriterionError",
    "CriterionRecord",
    "CriterionResult",
    "DriveEvaluator",
    "DriveScore",
    "EvaluationSettings",
    "Infraction",
    "InfractionKind",
    "InfractionRecord",
    "InfractionWatch",
    "Metrics",
    "Route",
    "RouteError",
    "ScoreRecord",
    "driving_score",
    "ego_sample",
    "parse_criterion",
    "penalty_factor",
]
