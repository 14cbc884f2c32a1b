"""A road's reference line in the map frame: position, heading and height at stations."""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from egosim.world.arrays import FloatArray
from egosim.world.map.opendrive.document import Road
from egosim.world.map.opendrive.geometry import Arc, Geometry, Line, Spiral, evaluate
from egosim.world.map.opendrive.polynomials import evaluate as evaluate_cubics

# A 0.02 rad turn between stations keeps chords within R·0.02²/8 (0.5 mm at R = 10 m) of
# the curve and their length within 0.002 % of its arc length.
MAX_TURN_RAD = 0.02
# Parametric cubics have no curvature bound at hand: this spacing, m.
PARAMETRIC_SPACING_M = 0.25
# However sharp a curve, stations stay at least this far apart, m.
MIN_SPACING_M = 0.05


def reference_poses(road: Road, s: FloatArray) -> FloatArray:
    """(N, 4) x, y, z, heading of the reference line at stations s (clamped to the road)."""
    s = np.clip(np.asarray(s, dtype=np.float64), 0.0, road.length)
    starts = np.array([start for start, _, _ in road.geometries])
    which = np.clip(np.searchsorted(starts, s, side="right") - 1, 0, len(starts) - 1)
    poses = np.empty((len(s), 4))
    for k, (start, pose, geometry) in enumerate(road.geometries):
        mask = which == k
        if np.any(mask):
            u = np.clip(s[mask] - start, 0.0, geometry.length)
            x, y, heading = evaluate(pose, geometry, u)
            poses[mask, 0], poses[mask, 1], poses[mask, 3] = x, y, heading
    poses[:, 2] = evaluate_cubics(road.elevation, s)
    return poses


def lateral_points(poses: FloatArray, t: npt.ArrayLike) -> FloatArray:
    """(N, 2) map points `t` metres left (+t) of reference-line poses (x, y, z, heading)."""
    heading = poses[:, 3]
    t = np.asarray(t, dtype=np.float64)
    return np.column_stack((poses[:, 0] - t * np.sin(heading), poses[:, 1] + t * np.cos(heading)))


def sample_stations(road: Road, step: float) -> FloatArray:
    """Stations every `step` metres, closer on curves (the heading turns at most
    MAX_TURN_RAD between stations), plus every geometry and lane-section boundary."""
    pieces: list[FloatArray | list[float]] = [
        [section.s for section in road.sections],
        [road.length],
    ]
    for start, _, geometry in road.geometries:
        spacing = min(step, MAX_TURN_RAD / max(_max_curvature(geometry), 1e-9))
        spacing = max(spacing, MIN_SPACING_M)
        pieces.append(start + np.arange(0.0, geometry.length, spacing))
    s = np.concatenate(pieces)
    s = np.unique(np.clip(s, 0.0, road.length))
    return s[np.concatenate(([True], np.diff(s) > 1e-6))]


def _max_curvature(geometry: Geometry) -> float:
    if isinstance(geometry, Line):
        return 0.0
    if isinstance(geometry, Arc):
        return abs(geometry.curvature)
    if isinstance(geometry, Spiral):
        return max(abs(geometry.curvature_start), abs(geometry.curvature_end))
    return MAX_TURN_RAD / PARAMETRIC_SPACING_M
