"""An optimum's multipliers as plain arrays (``solve.multipliers``): they continue a solve as the solution they
were read from does, after a pickle round trip too, and fit only an NLP of their size."""
import pickle

import numpy as np

from tests.solve.test_named_nlp import _box_problem
from transplanter.solve import NLPBuilder, Solver


def test_multipliers_continue_a_solve_as_their_solution_does_after_a_pickle_round_trip():
    layout = _box_problem()
    solver = Solver("box", layout)
    first = solver.solve({"x": 0.0, "y": 0.0, "z": [0.0, 0.0, 0.0]})
    multipliers = pickle.loads(pickle.dumps(first.multipliers()))
    np.testing.assert_array_equal(multipliers.lam_x, first.lam_x)
    np.testing.assert_array_equal(multipliers.lam_g, first.lam_g)
    lifted = layout.bounds().free_rows("sum")
    from_solution = solver.solve(first.values(), lifted, continues=first)
    from_arrays = solver.solve(first.values(), lifted, continues=multipliers)
    np.testing.assert_array_equal(from_arrays.x, from_solution.x)
    np.testing.assert_array_equal(from_arrays.lam_g, from_solution.lam_g)
    assert from_arrays.iterations == from_solution.iterations


def test_multipliers_fit_only_an_nlp_with_as_many_variables_and_rows():
    layout = _box_problem()
    multipliers = Solver("box", layout).solve({"x": 0.0, "y": 0.0, "z": [0.0, 0.0, 0.0]}).multipliers()
    assert multipliers.fits(layout)
    other = NLPBuilder()
    x = other.variables("x", 5)
    other.constraints("sum", x[0] + x[1], 0.5, np.inf)
    assert not multipliers.fits(other.build(x[0] ** 2))
