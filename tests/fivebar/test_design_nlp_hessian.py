"""The design NLP's Hessian of the Lagrangian, formed through its grid quantities (``NLPBuilder.lifted``), is
CasADi's own Hessian of the NLP at a region candidate's start, slots in use, with any multipliers."""
import casadi as ca
import numpy as np

from transplanter.fivebar.nlp import build_nlp
from transplanter.fivebar.region import solution_region


def test_the_design_nlps_hessian_is_casadis_own(example_problem, rng):
    problem = example_problem
    nlp = build_nlp(problem, capacity=4)
    layout = nlp.layout
    assert layout.hessian is not None
    candidate = solution_region(problem).feasible[0]
    poses, turns = candidate.key_poses(problem)
    x = layout.vector(nlp.start(candidate.mech, candidate.relative_angle, candidate.stroke, problem.return_points,
                                poses, turns))
    p = layout.parameter_vector(nlp.parameters(float(candidate.mech.branch), np.array([0.3, 2.0, 4.1])))
    sigma, lam = ca.SX.sym("sigma"), ca.SX.sym("lam", layout.g.shape[0])
    own = ca.Function("own", [layout.x, layout.p, sigma, lam],
                      [ca.triu(ca.hessian(sigma * layout.f + ca.dot(lam, layout.g), layout.x)[0])])
    for _ in range(2):
        multipliers = rng.normal(size=layout.g.shape[0])
        lifted, expected = np.array(layout.hessian(x, p, 1.0, multipliers)), np.array(own(x, p, 1.0, multipliers))
        assert np.abs(lifted - expected).max() <= 1e-12 * np.abs(expected).max()
