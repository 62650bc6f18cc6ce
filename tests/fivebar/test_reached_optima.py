"""A refinement whose first solve reaches an earlier refinement's optimum, offered the same exchange turns,
ends as that one did (``fivebar.reached_optima``): the design is the one solving it through again gives."""
import numpy as np
import pytest

from transplanter.errors import SolverError
from transplanter.fivebar.design_solver import CONCAVITY_LIMIT, DesignSolver
from transplanter.fivebar.nlp import reach
from transplanter.fivebar.reached_optima import SAME_OPTIMUM, ReachedOptimum, reached
from transplanter.fivebar.region import solution_region


def test_only_a_first_solve_with_the_same_turns_branch_and_optimum_repeats_a_refinement():
    turns, x = np.array([0.5, 2.0]), np.linspace(0.0, 1.0, 5)
    known = ReachedOptimum(turns, 1.0, x, "design", np.array([0.5, 2.0, 3.0]))
    assert known.repeats(turns.copy(), 1.0, x + 0.5 * SAME_OPTIMUM)
    assert not known.repeats(turns, 1.0, x + 2 * SAME_OPTIMUM)
    assert not known.repeats(turns, -1.0, x)
    assert not known.repeats(np.array([0.5, 2.1]), 1.0, x) and not known.repeats(turns[:1], 1.0, x)
    other = ReachedOptimum(turns[:1], 1.0, x, "other", turns)
    assert reached((other, known), turns, 1.0, x) is known and reached((other,), turns, 1.0, x) is None


@pytest.fixture(scope="module")
def region(example_problem):
    return solution_region(example_problem)


def test_a_start_that_reaches_a_known_optimum_gets_the_design_solving_it_again_gives(example_problem, region):
    """Two starts whose first solves end at one optimum (offered no exchange turns): the second refinement
    is taken from the first (no solve after its first), and equals the second start refined on a solver that
    has not seen the first, to the solver's tolerance; the exchange turns left are the first's."""
    problem = example_problem
    starts, solver = [], DesignSolver(problem)   # a first solve leaves the solver as it was: one serves all
    unseen = solver.twin()                       # the solver as built, sharing its built Functions (no build)
    for candidate in region.feasible:
        try:
            solution = solver.solve(candidate, curvature_floor=-CONCAVITY_LIMIT, closure_in_quality=True)
        except SolverError:         # a start that does not converge is no use here
            continue
        assert solution.solved is not None
        if starts and np.abs(solution.solved.x - starts[0][1]).max() <= SAME_OPTIMUM:
            starts.append((candidate, solution.solved.x))
            break
        if not starts:
            starts.append((candidate, solution.solved.x))
    assert len(starts) == 2, "two starts of the example reach one optimum"
    (first, _), (second, _) = starts
    assert solver.reached == () and solver.exchange_turns.size == 0 and solver.builds == 1   # as built: fresh
    design = solver.refine(first)
    left = solver.exchange_turns
    solver.exchange_turns = np.empty(0)           # the second start is offered what the first was
    repeated = solver.refine(second)
    assert solver.repeats == 1 and repeated is design and np.array_equal(solver.exchange_turns, left)
    again = unseen.refine(second)
    size = reach(problem)
    assert abs(repeated.objective - again.objective) <= 1e-9 * abs(again.objective)
    for name in ("carrier_length", "rod_length", "receiving_length"):
        assert abs(getattr(repeated.mech, name) - getattr(again.mech, name)) <= 1e-7 * size
    for name in ("hinge_b", "e_local", "f_local"):
        assert np.abs(getattr(repeated.mech, name) - getattr(again.mech, name)).max() <= 1e-7 * size
