"""A road's reference line in the map frame: position, heading and height at stations."""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from egosim.world.map.opendrive.document import Road
from egosim.world.map.opendrive.geometry import evaluate
from egosim.world.map.opendrive.polynomials import evaluate as evaluate_cubics

FloatArray = npt.NDArray[np.float64]


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


def sample_stations(road: Road, step: float) -> FloatArray:
    """Stations every `step` metres plus every geometry and lane-section boundary."""
    breaks = [start for start, _, _ in road.geometries] + [section.s for section in road.sections]
    s = np.concatenate((np.arange(0.0, road.length, step), breaks, [road.length]))
    s = np.unique(np.clip(s, 0.0, road.length))
    return s[np.concatenate(([True], np.diff(s) > 1e-6))]
