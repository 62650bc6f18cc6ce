"""The Burmester derivation (Wang et al. 2025, eq 1-2): the consistency determinant of four poses is the circular
cubic of eq (2), the generated cubic coefficients reproduce it, and the five-pose pencil resultant carries the
circular factor."""
import numpy as np
import pytest
import sympy as sp

from derivations import burmester
from transplanter._generated import burmester as generated_burmester
from transplanter.generated import casadi_function

x, y = sp.symbols("curve_x curve_y", real=True)


@pytest.fixture(scope="module", params=["center", "circle"])
def determinant(request):
    _, poses = burmester._pose_symbols(4)
    det, trig = burmester.consistency_determinant(poses, request.param, (x, y))
    return request.param, det, trig


def test_determinant_is_the_circular_cubic_of_eq2(determinant):
    """The 3x3 consistency determinant equals H1(x^3+xy^2) + H2(y^3+yx^2) + ... exactly, with H1..H8
    read off it, free of x and y, and H1, H2 not both zero: so it is a cubic with no other monomials,
    and x^3, x y^2 (and y^3, x^2 y) share their coefficients (the difference, as a polynomial in x
    and y, is zero)."""
    _, det, _ = determinant
    h = burmester.cubic_coefficients(det, x, y)
    assert not any(c.has(x, y) for c in h)
    assert (det - sp.Poly(burmester.circular_cubic(h, x, y), x, y)).is_zero
    assert any(sp.expand(c) != 0 for c in h[:2]), "the cubic part must not vanish identically"


def test_generated_cubic_is_the_determinant(determinant, rng):
    """The generated H1..H8 reproduce the symbolic determinant at seeded real points."""
    kind, det, trig = determinant
    (xs, ys, angles), _ = burmester._pose_symbols(4)
    function = casadi_function(getattr(generated_burmester, f"burmester_{kind}_cubic"))
    reference = sp.lambdify([*xs, *ys, *angles, x, y], det.as_expr().subs(trig), "numpy")
    for _ in range(5):
        pose = rng.normal(size=(4, 3))
        point = rng.normal(size=2)
        h = np.asarray(function(pose[:, 0], pose[:, 1], pose[:, 2])).ravel()
        value = burmester.circular_cubic(h, *point)
        expected = reference(*pose[:, 0], *pose[:, 1], *pose[:, 2], *point)
        assert value == pytest.approx(expected, rel=1e-10, abs=1e-12)


def test_pencil_resultant_has_the_circular_factor():
    """The degree-8 resultant of the two pencil quadratics is divisible by 1 + tau^2."""
    h, k, pivot = sp.symbols("h1:9"), sp.symbols("k1:9"), sp.symbols("p1:3")
    quotient, remainder = burmester.pencil_resultant(h, k, pivot, sp.Symbol("tau"))
    assert remainder.is_zero
    assert quotient.degree() == 6
