"""Reference-line geometries of OpenDRIVE's plan view, evaluated at stations along them.

Line and arc are closed forms. A spiral (clothoid) has curvature k0 + c·u; its heading is
the integral of curvature (closed form) and its position the integral of the heading's
cosine and sine, taken by 8-point Gauss-Legendre quadrature between consecutive stations.
poly3 and paramPoly3 are parametric cubics (u(p), v(p)) in the frame of their start; a table
of arc length over p maps stations to p.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from egosim.world.arrays import FloatArray

_GAUSS_NODES, _GAUSS_WEIGHTS = np.polynomial.legendre.leggauss(8)
# Arc-length tables of parametric cubics hold this many intervals per metre (at least 64).
_TABLE_INTERVALS_PER_M = 4.0


@dataclass(frozen=True)
class Pose2:
    """Start of a geometry: position and heading (rad) in the map frame."""

    x: float
    y: float
    heading: float


@dataclass(frozen=True)
class Line:
    length: float


@dataclass(frozen=True)
class Arc:
    length: float
    curvature: float


@dataclass(frozen=True)
class Spiral:
    length: float
    curvature_start: float
    curvature_end: float


@dataclass(frozen=True)
class ParamPoly3:
    """u(p) = aU + bU p + cU p² + dU p³ and v(p) likewise, p in [0, p_end].

    `p_end` is 1 for pRange="normalized", `length` for "arcLength". A poly3 is a
    paramPoly3 with u = p (`u_is_p`), p running until the arc length reaches `length`.
    """

    length: float
    u: tuple[float, float, float, float]
    v: tuple[float, float, float, float]
    p_end: float
    u_is_p: bool = False


Geometry = Line | Arc | Spiral | ParamPoly3


def evaluate_local(geometry: Geometry, u: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
    """(x, y, heading) at stations u in [0, length] in the geometry's own frame."""
    if isinstance(geometry, Line):
        return u.copy(), np.zeros_like(u), np.zeros_like(u)
    if isinstance(geometry, Arc):
        k = geometry.curvature
        if abs(k) < 1e-12:
            return u.copy(), np.zeros_like(u), np.zeros_like(u)
        heading = k * u
        return np.sin(heading) / k, (1.0 - np.cos(heading)) / k, heading
    if isinstance(geometry, Spiral):
        rate = (geometry.curvature_end - geometry.curvature_start) / geometry.length
        k0 = geometry.curvature_start

        def heading_at(s: FloatArray) -> FloatArray:
            return k0 * s + 0.5 * rate * s * s

        x = _integrate(lambda s: np.cos(heading_at(s)), u)
        y = _integrate(lambda s: np.sin(heading_at(s)), u)
        return x, y, heading_at(u)
    return _parametric(geometry, u)


def evaluate(
    start: Pose2, geometry: Geometry, u: FloatArray
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """(x, y, heading) in the map frame at stations u along a geometry starting at `start`."""
    lx, ly, lh = evaluate_local(geometry, u)
    cos_h, sin_h = math.cos(start.heading), math.sin(start.heading)
    return (
        start.x + lx * cos_h - ly * sin_h,
        start.y + lx * sin_h + ly * cos_h,
        start.heading + lh,
    )


def _integrate(integrand: Callable[[FloatArray], FloatArray], u: FloatArray) -> FloatArray:
    """∫_0^u integrand for each u (any order), by Gauss-Legendre between sorted stations."""
    knots, where = np.unique(np.concatenate(([0.0], u)), return_inverse=True)
    a, b = knots[:-1, None], knots[1:, None]
    nodes = 0.5 * (a + b) + 0.5 * (b - a) * _GAUSS_NODES
    pieces = 0.5 * (b - a)[:, 0] * (integrand(nodes) @ _GAUSS_WEIGHTS)
    return np.concatenate(([0.0], np.cumsum(pieces)))[where[1:]]


def _cubic(c: tuple[float, float, float, float], p: FloatArray) -> FloatArray:
    return c[0] + p * (c[1] + p * (c[2] + p * c[3]))


def _cubic_slope(c: tuple[float, float, float, float], p: FloatArray) -> FloatArray:
    return c[1] + p * (2.0 * c[2] + p * 3.0 * c[3])


def _parametric(geometry: ParamPoly3, u: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
    # A poly3's p (= u) never runs further than its arc length, so [0, length] brackets it.
    p_end = geometry.length if geometry.u_is_p else geometry.p_end
    intervals = max(64, math.ceil(geometry.length * _TABLE_INTERVALS_PER_M))
    p_table = np.linspace(0.0, p_end, intervals + 1)

    def speed(p: FloatArray) -> FloatArray:
        return np.hypot(_cubic_slope(geometry.u, p), _cubic_slope(geometry.v, p))

    s_table = _integrate(speed, p_table)
    p = np.interp(u, s_table, p_table)
    heading = np.arctan2(_cubic_slope(geometry.v, p), _cubic_slope(geometry.u, p))
    return _cubic(geometry.u, p), _cubic(geometry.v, p), heading
