"""Reference-line geometry against closed forms."""

import math

import numpy as np
import pytest

from egosim.world.map.opendrive import Arc, Line, ParamPoly3, Pose2, Spiral, evaluate
from egosim.world.map.opendrive.polynomials import Cubic
from egosim.world.map.opendrive.polynomials import evaluate as evaluate_cubics

START = Pose2(12.0, -7.0, 0.4)


def fresnel_path(rate: float, s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """∫0^s cos(rate u²/2) du and ∫0^s sin(rate u²/2) du by their power series."""
    x = np.zeros_like(s)
    y = np.zeros_like(s)
    half = rate / 2.0
    for n in range(12):
        x += (-1) ** n * half ** (2 * n) * s ** (4 * n + 1) / (math.factorial(2 * n) * (4 * n + 1))
        y += (
            (-1) ** n
            * half ** (2 * n + 1)
            * s ** (4 * n + 3)
            / (math.factorial(2 * n + 1) * (4 * n + 3))
        )
    return x, y


def test_line_runs_along_its_heading():
    s = np.linspace(0.0, 50.0, 11)
    x, y, heading = evaluate(START, Line(50.0), s)
    assert x == pytest.approx(START.x + s * math.cos(START.heading))
    assert y == pytest.approx(START.y + s * math.sin(START.heading))
    assert heading == pytest.approx(np.full_like(s, START.heading))


@pytest.mark.parametrize("curvature", [0.02, -0.05, 0.1])
def test_arc_keeps_its_radius_and_turns_at_its_curvature(curvature):
    s = np.linspace(0.0, 60.0, 31)
    x, y, heading = evaluate(START, Arc(60.0, curvature), s)
    radius = 1.0 / curvature
    cx = START.x - radius * math.sin(START.heading)
    cy = START.y + radius * math.cos(START.heading)
    assert np.hypot(x - cx, y - cy) == pytest.approx(np.full_like(s, abs(radius)))
    assert heading == pytest.approx(START.heading + curvature * s)


@pytest.mark.parametrize("curvature_end", [0.01, -0.04])
def test_clothoid_from_straight_follows_the_fresnel_integrals(curvature_end):
    length = 80.0
    rate = curvature_end / length
    s = np.linspace(0.0, length, 17)
    x, y, heading = evaluate(Pose2(0.0, 0.0, 0.0), Spiral(length, 0.0, curvature_end), s)
    fx, fy = fresnel_path(rate, s)
    assert x == pytest.approx(fx, abs=1e-9)
    assert y == pytest.approx(fy, abs=1e-9)
    assert heading == pytest.approx(rate * s**2 / 2)


def test_clothoid_curvature_grows_at_its_rate():
    length, k0, k1 = 100.0, -0.01, 0.03
    s = np.linspace(0.0, length, 2001)
    x, y, _ = evaluate(START, Spiral(length, k0, k1), s)
    # Curvature of the sampled curve: turn of the chord direction per metre.
    chords = np.unwrap(np.arctan2(np.diff(y), np.diff(x)))
    curvature = np.diff(chords) / np.diff(s)[1:]
    mid = s[1:-1]
    assert curvature == pytest.approx(k0 + (k1 - k0) / length * mid, abs=1e-6)


def test_clothoid_of_constant_curvature_is_an_arc():
    s = np.linspace(0.0, 40.0, 9)
    spiral = evaluate(START, Spiral(40.0, 0.05, 0.05), s)
    arc = evaluate(START, Arc(40.0, 0.05), s)
    for a, b in zip(spiral, arc, strict=True):
        assert a == pytest.approx(b, abs=1e-9)


def test_poly3_straight_slope_is_a_3_4_5_triangle():
    # v = 0.75 u: 10 m of curve reach u = 8, v = 6.
    geometry = ParamPoly3(10.0, (0.0, 1.0, 0.0, 0.0), (0.0, 0.75, 0.0, 0.0), 10.0, u_is_p=True)
    x, y, heading = evaluate(Pose2(0.0, 0.0, 0.0), geometry, np.array([0.0, 5.0, 10.0]))
    assert x == pytest.approx([0.0, 4.0, 8.0])
    assert y == pytest.approx([0.0, 3.0, 6.0])
    assert heading == pytest.approx(np.full(3, math.atan2(3, 4)))


@pytest.mark.parametrize("normalized", [True, False])
def test_param_poly3_parabola_is_found_by_arc_length(normalized):
    # u = p, v = p² over p in [0, 2]: arc length to p is p√(1+4p²)/2 + asinh(2p)/4.
    def arc_length(p: float) -> float:
        return p * math.sqrt(1 + 4 * p * p) / 2 + math.asinh(2 * p) / 4

    length = arc_length(2.0)
    if normalized:  # p = 2q, q in [0, 1]
        geometry = ParamPoly3(length, (0.0, 2.0, 0.0, 0.0), (0.0, 0.0, 4.0, 0.0), 1.0)
    else:  # pRange arcLength: p in [0, length], u = 2p / length
        k = 2.0 / length
        geometry = ParamPoly3(length, (0.0, k, 0.0, 0.0), (0.0, 0.0, k * k, 0.0), length)
    x, y, heading = evaluate(Pose2(0.0, 0.0, 0.0), geometry, np.array([arc_length(1.0)]))
    assert (x[0], y[0]) == pytest.approx((1.0, 1.0), abs=1e-6)
    assert heading[0] == pytest.approx(math.atan(2.0), abs=1e-6)


def test_piecewise_cubic_restarts_at_each_record():
    records = (Cubic(0.0, 1.0, 0.5, 0.0, 0.0), Cubic(10.0, 2.0, 0.0, 0.1, 0.01))
    s = np.array([0.0, 4.0, 10.0, 12.0])
    assert evaluate_cubics(records, s) == pytest.approx([1.0, 3.0, 2.0, 2.0 + 0.4 + 0.08])
    assert evaluate_cubics((), s) == pytest.approx(np.zeros(4))
