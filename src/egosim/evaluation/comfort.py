"""Comfort figures of a drive: peak and RMS acceleration and jerk, both axes."""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from egosim.world.arrays import FloatArray


def _peak(values: FloatArray) -> float:
    return float(np.max(np.abs(values))) if len(values) else 0.0


def _rms(values: FloatArray) -> float:
    return float(np.sqrt(np.mean(values * values))) if len(values) else 0.0


def comfort_figures(
    times_s: npt.ArrayLike, longitudinal_mps2: npt.ArrayLike, lateral_mps2: npt.ArrayLike
) -> dict[str, float]:
    """Max |.| and RMS of the body-frame accelerations sampled at `times_s` and of their
    jerks (finite differences between samples)."""
    t = np.asarray(times_s, dtype=np.float64)
    figures: dict[str, float] = {}
    for axis, samples in (("long", longitudinal_mps2), ("lat", lateral_mps2)):
        accel = np.asarray(samples, dtype=np.float64)
        dt = np.diff(t)
        jerk = np.diff(accel)[dt > 0] / dt[dt > 0]
        figures[f"max_{axis}_accel_mps2"] = _peak(accel)
        figures[f"rms_{axis}_accel_mps2"] = _rms(accel)
        figures[f"max_{axis}_jerk_mps3"] = _peak(jerk)
        figures[f"rms_{axis}_jerk_mps3"] = _rms(jerk)
    return figures


def lane_error_figures(lateral_errors_m: npt.ArrayLike) -> dict[str, float]:
    """Max and RMS distance of the ego from its lane's centre, m."""
    errors = np.asarray(lateral_errors_m, dtype=np.float64)
    return {"max_lateral_error_m": _peak(errors), "rms_lateral_error_m": _rms(errors)}
