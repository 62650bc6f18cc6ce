"""The one place a convex quadratic program meets a solver (``casadi.conic`` with DAQP, a dual active-set
method), small and dense:

    minimise 1/2 x' H x + g' x  subject to  lower <= A x <= upper  (equal bounds: an equality row).

One solver is built per shape (rows rounded up to a multiple of ``ROW_STEP``, the spare rows free) and
reused. Success is the solver's own; anything else (the rows infeasible, or it gave up) raises a
``SolverError`` naming the solver's status.
"""
from __future__ import annotations

import functools

import casadi as ca
import numpy as np

from transplanter.errors import SolverError

#: Solvers are built for row counts in steps of this many (the spare rows have no bounds).
ROW_STEP = 16
#: How far a row may be off its bounds at a solution (DAQP's own default, 1e-6, is loose for callers that check
#: their rows again to 1e-9).
PRIMAL_TOLERANCE = 1e-10


@functools.lru_cache(maxsize=16)
def _solver(variables: int, rows: int) -> ca.Function:
    shapes = {"h": ca.Sparsity.dense(variables, variables), "a": ca.Sparsity.dense(rows, variables)}
    return ca.conic("qp", "daqp", shapes, {"error_on_fail": False, "daqp": {"primal_tol": PRIMAL_TOLERANCE}})


def solve_qp(h: np.ndarray, g: np.ndarray, a: np.ndarray, lower: np.ndarray, upper: np.ndarray) -> np.ndarray:
    """The minimiser x; a ``SolverError`` when the solver reports no solution."""
    rows, variables = a.shape
    spare = -rows % ROW_STEP
    solver = _solver(variables, rows + spare)
    result = solver(h=h, g=g, a=np.r_[a, np.zeros((spare, variables))], lba=np.r_[lower, np.full(spare, -np.inf)],
                    uba=np.r_[upper, np.full(spare, np.inf)])
    stats = solver.stats()
    if not stats["success"]:
        raise SolverError("the quadratic program has no solution", str(stats["return_status"]))
    return np.asarray(result["x"]).ravel()
