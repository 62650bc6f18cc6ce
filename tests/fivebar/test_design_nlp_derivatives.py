"""The design NLP's Hessian of the Lagrangian and its rows' Jacobian, formed through its grid quantities
(``NLPBuilder.lifted``), are CasADi's own of the NLP at a region candidate's start, slots in use (the Hessian with
any multipliers)."""
import casadi as ca
import numpy as np
import pytest

from transplanter.fivebar.nlp import build_nlp
from transplanter.fivebar.region import solution_region


@pytest.fixture(scope="module")
def at_a_start(example_problem):
    """The design NLP with room for 4 exchange slots, and a region candidate's start with 3 of them in use."""
    problem = example_problem
    nlp = build_nlp(problem, capacity=4)
    candidate = solution_region(problem).feasible[0]
    poses, turns = candidate.key_poses(problem)
    layout = nlp.layout
    x = layout.vector(nlp.start(candidate.mech, candidate.relative_angle, candidate.stroke, problem.return_points,
                                poses, turns))
    return layout, x, layout.parameter_vector(nlp.parameters(float(candidate.mech.branch), np.array([0.3, 2.0, 4.1])))


def test_the_design_nlps_hessian_is_casadis_own(at_a_start, rng):
    layout, x, p = at_a_start
    assert layout.hessian is not None
    sigma, lam = ca.SX.sym("sigma"), ca.SX.sym("lam", layout.g.shape[0])
    own = ca.Function("own", [layout.x, layout.p, sigma, lam],
                      [ca.triu(ca.hessian(sigma * layout.f + ca.dot(lam, layout.g), layout.x)[0])])
    for _ in range(2):
        multipliers = rng.normal(size=layout.g.shape[0])
        lifted, expected = np.array(layout.hessian(x, p, 1.0, multipliers)), np.array(own(x, p, 1.0, multipliers))
        assert np.abs(lifted - expected).max() <= 1e-12 * np.abs(expected).max()


def test_the_design_nlps_jacobian_is_casadis_own(at_a_start):
    layout, x, p = at_a_start
    assert layout.jacobian is not None
    own = ca.Function("own", [layout.x, layout.p], [ca.jacobian(layout.g, layout.x)])
    lifted, expected = layout.jacobian(x, p)[1], own(x, p)
    assert lifted.sparsity() == expected.sparsity()
    assert np.abs(np.array(lifted) - np.array(expected)).max() <= 1e-12 * np.abs(np.array(expected)).max()
