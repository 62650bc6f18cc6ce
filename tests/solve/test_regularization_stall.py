"""The stall rule on IPOPT's Hessian regularisation: a solve is stopped at the first iteration that ends a run
of ``regularized_iterations`` iterations regularised by at least ``regularization``, read from the solve's own
statistics while it runs. The ground truth is the same solve without the rule: IPOPT's path does not depend
on the watch, so the stop must fall exactly where that path's regularisation first has such a run."""
import casadi as ca
import numpy as np
import pytest

from transplanter.errors import SolverError
from transplanter.solve import NLPBuilder, Solver, StallRule

#: min sum cos(x) over 0 <= x <= 4 from near x = 0, where the Hessian -cos(x) is negative definite: IPOPT
#: corrects the inertia by regularising, off and on, until every x passes pi / 2 (the optimum: x = pi).
START = {"x": [0.01, 0.02, 0.03]}


def _layout():
    nlp = NLPBuilder()
    x = nlp.variables("x", 3, 0.0, 4.0)
    nlp.constraints("total", ca.sum1(x), -np.inf, 100.0)       # never binds: the violation rule stays quiet
    return nlp.build(ca.sum1(ca.cos(x)))


def _runs(sizes: np.ndarray, threshold: float) -> np.ndarray:
    """At each iterate, how many iterates in a row up to it have ``sizes`` >= ``threshold``."""
    runs = np.zeros(len(sizes), int)
    for index, size in enumerate(sizes):
        runs[index] = (runs[index - 1] + 1 if index else 1) if size >= threshold else 0
    return runs


@pytest.fixture(scope="module")
def free_path():
    """The solve without a stall rule, and the regularisation IPOPT added at each of its iterations."""
    solver = Solver("free", _layout())
    solution = solver.solve(START)
    return solution, np.array(solver.function.stats()["iterations"]["regularization_size"])


@pytest.mark.parametrize("threshold, run", [(1.0, 3), (2.0, 2), (0.5, 5)])
def test_a_run_of_regularised_iterations_stops_the_solve_where_the_free_path_has_it(free_path, threshold, run):
    solution, sizes = free_path
    reached = np.flatnonzero(_runs(sizes, threshold) == run)
    assert reached.size and reached[0] < solution.iterations, "the free path has such a run before it converges"
    end = int(reached[0])
    rule = StallRule(violation=1e-3, iterations=100, regularization=threshold, regularized_iterations=run)
    solver = Solver("watched", _layout(), stall=rule)
    with pytest.raises(SolverError) as raised:
        solver.solve(START)
    assert solver.watch.stalled and solver.watch.count == end + 1
    stopped = np.array(solver.function.stats()["iterations"]["regularization_size"])
    np.testing.assert_array_equal(stopped, sizes[:end + 1])       # the same path up to the stop
    assert raised.value.status == (f"a stall (the Hessian regularisation at or above {threshold:g} for {run} "
                                   f"iterations in a row, after {end + 1})")


def test_a_path_never_regularised_that_much_is_left_to_converge(free_path):
    solution, sizes = free_path
    rule = StallRule(violation=1e-3, iterations=100, regularization=2 * sizes.max(), regularized_iterations=1)
    solver = Solver("watched", _layout(), stall=rule)
    watched = solver.solve(START)
    assert not solver.watch.stalled and watched.iterations == solution.iterations
    np.testing.assert_array_equal(watched.x, solution.x)


def test_the_run_restarts_after_an_iteration_below_the_threshold(free_path):
    """A run one longer than the free path's longest run at a threshold never completes: the count restarts
    at every iteration below it, so the solve converges."""
    solution, sizes = free_path
    longest = int(_runs(sizes, 1.0).max())
    assert 1 < longest < int(np.sum(sizes >= 1.0)), "runs broken by iterations below the threshold"
    rule = StallRule(violation=1e-3, iterations=100, regularization=1.0, regularized_iterations=longest + 1)
    solver = Solver("watched", _layout(), stall=rule)
    assert solver.solve(START).iterations == solution.iterations and not solver.watch.stalled

