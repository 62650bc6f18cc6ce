"""The Hessian of the Lagrangian and the rows' Jacobian formed through lifted quantities (``NLPBuilder.lifted``,
``solve.lifted_hessian``, ``solve.lifted_jacobian``) are CasADi's own of the same NLP, and IPOPT reaches the same
optimum with them."""
import casadi as ca
import numpy as np
import pytest

from transplanter.solve import NLPBuilder, Solver


def _curved_problem(lift: bool):
    """min (x0 - 1)^2 + (x1 - 2)^2 + x2^2 with points on a circle of radius |x| seen through an affine
    quantity of the parameters (angles c + p x2) and a nonlinear one (|x|): the same NLP with or without
    the quantities lifted."""
    nlp = NLPBuilder()
    x = nlp.variables("x", 3, -5.0, 5.0)
    shift = nlp.parameters("shift")
    turns = np.linspace(0.0, 2 * np.pi, 7, endpoint=False)
    angles = ca.DM(turns) + shift * x[2] + x[0]
    radius = ca.norm_2(x)
    if lift:
        angles, radius = nlp.lifted("angles", angles), nlp.lifted("radius", radius)
    nlp.constraints("points", radius * ca.cos(angles) + x[1] * ca.sin(angles) ** 2, -np.inf, 1.5)
    nlp.constraints("ring", radius ** 2, 1.0, 9.0)
    return nlp.build((x[0] - 1) ** 2 + (x[1] - 2) ** 2 + x[2] ** 2)


def _own_hessian(layout) -> ca.Function:
    sigma, lam = ca.SX.sym("sigma"), ca.SX.sym("lam", layout.g.shape[0])
    hessian = ca.hessian(sigma * layout.f + ca.dot(lam, layout.g), layout.x)[0]
    return ca.Function("own", [layout.x, layout.p, sigma, lam], [ca.triu(hessian)])


def test_the_lifted_hessian_is_casadis_own_of_the_same_nlp(rng):
    layout = _curved_problem(lift=True)
    plain = _curved_problem(lift=False)
    assert layout.hessian is not None and plain.hessian is None
    own = _own_hessian(layout)
    for _ in range(5):
        x, p, sigma, lam = rng.normal(size=3), rng.normal(size=1), rng.normal(), rng.normal(size=8)
        lifted, expected = np.array(layout.hessian(x, p, sigma, lam)), np.array(own(x, p, sigma, lam))
        assert np.abs(lifted - expected).max() <= 1e-12 * np.abs(expected).max()
        values = [np.array(ca.Function("v", [s.x, s.p], [s.f, s.g])(x, p)[k]) for s in (layout, plain) for k in (0, 1)]
        assert np.array_equal(values[0], values[2]) and np.array_equal(values[1], values[3])


def test_the_lifted_jacobian_is_casadis_own_of_the_same_nlp(rng):
    layout = _curved_problem(lift=True)
    assert layout.jacobian is not None and _curved_problem(lift=False).jacobian is None
    own = ca.Function("own", [layout.x, layout.p], [layout.g, ca.jacobian(layout.g, layout.x)])
    for _ in range(5):
        x, p = rng.normal(size=3), rng.normal(size=1)
        (rows, lifted), (own_rows, expected) = layout.jacobian(x, p), own(x, p)
        assert np.abs(np.array(rows) - np.array(own_rows)).max() <= 1e-14 * np.abs(np.array(own_rows)).max()
        assert np.abs(np.array(lifted) - np.array(expected)).max() <= 1e-12 * np.abs(np.array(expected)).max()


def test_ipopt_reaches_the_same_optimum_through_the_lifted_hessian():
    start = {"x": [0.5, 0.5, 0.5]}
    lifted = Solver("lifted", _curved_problem(lift=True)).solve(start, parameters={"shift": 0.3})
    plain = Solver("plain", _curved_problem(lift=False)).solve(start, parameters={"shift": 0.3})
    assert lifted.x == pytest.approx(plain.x, abs=1e-9)
    assert lifted.objective == pytest.approx(plain.objective, abs=1e-12)
    assert lifted.row("points").max() <= 1.5 + 1e-9 and np.linalg.norm(lifted.x) >= 1.0 - 1e-9
