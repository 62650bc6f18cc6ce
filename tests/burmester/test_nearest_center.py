"""The true nearest point of a four-pose center-point curve, against points built at a known distance."""
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

from derivations.burmester import circular_cubic
from transplanter.burmester import load_problem, nearest_center, synthesize
from transplanter.burmester.five_poses import center_cubic
from transplanter.errors import ProblemError
from transplanter.geometry.poses import Frame

ROOT = Path(__file__).resolve().parents[2]
X, Y = sp.symbols("x y", real=True)


@pytest.fixture(scope="module")
def table1():
    return synthesize(load_problem(ROOT / "examples/burmester_4poses.toml"))


def _cubic_and_gradient(result):
    """h(x, y) of eq (2) in world mm and its gradient, from the derived coefficients (sympy, not the package)."""
    frame = Frame.of(result.problem.poses)
    h = center_cubic(frame.local_poses(result.problem.poses))
    x, y = (X - frame.origin[0]) / frame.scale, (Y - frame.origin[1]) / frame.scale      # frame.to_local, symbolic
    c, s = np.cos(frame.angle), np.sin(frame.angle)
    local = (c * x + s * y, -s * x + c * y)
    expr = circular_cubic([sp.Float(c) for c in h], *local)
    value = sp.lambdify((X, Y), expr, "numpy")
    gradient = sp.lambdify((X, Y), [sp.diff(expr, X), sp.diff(expr, Y)], "numpy")
    return value, lambda p: np.array(gradient(*p), float)


def test_point_off_the_curve_along_its_normal_comes_back(table1):
    """q on the curve, p = q + d n with n the unit normal of the cubic at q: the nearest point is q, at
    distance d, for d well inside the curve's radius of curvature."""
    value, gradient = _cubic_and_gradient(table1)
    scale = table1.dyads[0].scale
    for k in (100, 500, 900):
        q = table1.dyads[k].center
        assert abs(value(*q)) < 1e-9 * np.abs(gradient(q)).max()      # the traced dyad is on the curve
        normal = gradient(q) / np.linalg.norm(gradient(q))
        d = 1e-3 * scale
        found = nearest_center(table1, q + d * normal)
        assert found.distance_mm == pytest.approx(d, rel=1e-6)
        assert np.linalg.norm(found.dyad.center - q) < 1e-6 * scale
        assert found.dyad.max_residual_mm < 1e-9 * scale


def test_published_hinge_lies_on_the_normal_through_its_foot(table1):
    """At the foot G of the perpendicular from p: h(G) = 0 and p - G is parallel to grad h(G); the
    distance is no more than the nearest sample's and the dyad keeps its length through the poses."""
    value, gradient = _cubic_and_gradient(table1)
    p = np.array([-78.83, -33.37])
    found = nearest_center(table1, p)
    g = found.dyad.center
    assert abs(value(*g)) < 1e-9 * np.abs(gradient(g)).max()
    offset = (p - g) / np.linalg.norm(p - g)
    normal = gradient(g) / np.linalg.norm(gradient(g))
    assert abs(offset[0] * normal[1] - offset[1] * normal[0]) < 1e-7
    assert found.distance_mm < found.sample_distance_mm
    assert found.dyad.max_residual_mm < 1e-9 * found.dyad.scale


def test_needs_four_poses():
    five = synthesize(load_problem(ROOT / "examples/burmester_5poses.toml"))
    with pytest.raises(ProblemError, match="four poses"):
        nearest_center(five, [0.0, 0.0])


def test_given_length_returns_the_dyad_that_has_it(table1):
    """A traced dyad's own length and a point next to its center give that dyad back."""
    scale = table1.dyads[0].scale
    for k in (200, 700):
        dyad = table1.dyads[k]
        found = nearest_center(table1, dyad.center + [1e-3 * scale, -2e-3 * scale], length=dyad.length)
        assert found.dyad.length == pytest.approx(dyad.length, rel=1e-12)
        assert np.linalg.norm(found.dyad.center - dyad.center) < 1e-6 * scale
        assert np.linalg.norm(found.dyad.circle - dyad.circle) < 1e-6 * scale
