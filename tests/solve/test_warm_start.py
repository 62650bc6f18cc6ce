"""A re-solve that continues an optimum starts from its multipliers (``Solver.solve``'s ``continues``), on
problems whose answer is known in closed form."""
import numpy as np
import pytest

from tests.solve.test_named_nlp import _box_problem
from transplanter.solve import Solver
from transplanter.solve.ipopt import held_multipliers


def test_multipliers_of_a_side_without_a_bound_start_at_zero():
    # CasADi's sign: negative on a lower bound, positive on an upper one
    multipliers = np.array([-2.0, 3.0, -4.0, 5.0, 0.0])
    lower = np.array([0.0, -np.inf, -np.inf, 1.0, -np.inf])
    upper = np.array([np.inf, 1.0, 2.0, np.inf, np.inf])
    assert held_multipliers(multipliers, lower, upper).tolist() == [-2.0, 3.0, 0.0, 0.0, 0.0]


def test_a_continued_solve_reaches_the_optimum_of_its_own_bounds_with_the_multipliers_it_was_given():
    """The box problem's optimum x = 1, y = -0.5 (x <= 1 and x + y >= 0.5 on). Continued from it with the
    same bounds it stays there, with the same multipliers; with x + y >= 0.5 lifted (its multiplier dropped)
    it moves to y = -1, the unconstrained value, as a cold solve of those bounds does."""
    layout = _box_problem()
    solver = Solver("box", layout)
    first = solver.solve({"x": 0.0, "y": 0.0, "z": [0.0, 0.0, 0.0]})
    again = solver.solve(first.values(), continues=first)
    assert again.x == pytest.approx(first.x, abs=1e-9)
    assert again.lam_g == pytest.approx(first.lam_g, abs=1e-8) and again.lam_x == pytest.approx(first.lam_x, abs=1e-8)
    lifted = layout.bounds().free_rows("sum")
    moved = solver.solve(first.values(), lifted, continues=first)
    cold = solver.solve(first.values(), layout.bounds().free_rows("sum"))
    assert moved["y"][0] == pytest.approx(-1.0, abs=1e-9) and moved.x == pytest.approx(cold.x, abs=1e-9)
    assert moved.row("sum") == pytest.approx([0.0], abs=1e-9) and moved.lam_g[0] == pytest.approx(0.0, abs=1e-9)
