"""Transition dynamics (OpenSCENARIO's DynamicsShape over a DynamicsDimension): how a
value goes from its start to its target, and how long that takes."""

from __future__ import annotations

import math

SHAPES = ("step", "linear", "cubic", "sinusoidal")
DIMENSIONS = ("time", "distance", "rate")


def progress(shape: str, fraction: float) -> float:
    """How far (0..1) a transition of `shape` is at `fraction` (0..1) of its length:
    linear, cubic (3f² - 2f³: no rate at either end), sinusoidal ((1 - cos πf)/2)."""
    f = min(max(fraction, 0.0), 1.0)
    if shape == "step":
        return 1.0
    if shape == "cubic":
        return f * f * (3.0 - 2.0 * f)
    if shape == "sinusoidal":
        return 0.5 * (1.0 - math.cos(math.pi * f))
    return f


def peak_rate_factor(shape: str) -> float:
    """A transition's highest rate over its mean rate: 1 for linear, 1.5 for cubic,
    π/2 for sinusoidal (so a rate-bounded transition of Δ takes factor·|Δ|/rate)."""
    return {"cubic": 1.5, "sinusoidal": math.pi / 2.0}.get(shape, 1.0)


def duration_at_rate(shape: str, change: float, rate: float) -> float:
    """Time (s) a transition of `change` takes when its rate never exceeds `rate`."""
    if shape == "step" or change == 0.0:
        return 0.0
    return peak_rate_factor(shape) * abs(change) / max(abs(rate), 1e-9)


def duration_at_peak_second_derivative(shape: str, change: float, limit: float) -> float:
    """Time (s) a transition of `change` takes when its second derivative (a lateral
    acceleration for an offset) never exceeds `limit`: cubic 6Δ/T², sinusoidal
    π²Δ/(2T²), linear as two constant halves 4Δ/T²."""
    if shape == "step" or change == 0.0:
        return 0.0
    factor = {"cubic": 6.0, "sinusoidal": math.pi**2 / 2.0}.get(shape, 4.0)
    return math.sqrt(factor * abs(change) / max(abs(limit), 1e-9))
